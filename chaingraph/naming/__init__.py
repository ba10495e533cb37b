"""Names: the bundled catalog, inversions named from it, identify, and the names of
the atlas's chains.

* :mod:`.catalog` the bundled catalog's files (:func:`catalog_path`);
* :mod:`.inversion_classes` :func:`inversions`: each link fixed in turn, grouped by
  structure, named from the catalog;
* :mod:`.identification` :func:`identify` a chain or mechanism in the catalog;
* :mod:`.atlas` the catalog's names of the atlas's chains and their mechanisms;
* :mod:`.linter` :func:`lint`: a chain file checked for what its author may not know.
"""

from chaingraph.naming.atlas import NamedMechanism, atlas_names, chain_names, named_mechanisms
from chaingraph.naming.catalog import catalog_dir, catalog_files, catalog_path, load_catalog
from chaingraph.naming.identification import Identification, identify
from chaingraph.naming.linter import Finding, finding_lines, lint
from chaingraph.naming.inversion_classes import (
    InputClass,
    Inversion,
    Inversions,
    catalog_matches,
    inversions,
    naming_matches,
)

__all__ = ["catalog_path", "catalog_dir", "catalog_files", "load_catalog", "inversions",
           "Inversions", "Inversion", "InputClass", "catalog_matches", "naming_matches",
           "identify", "Identification", "atlas_names", "chain_names", "named_mechanisms",
           "NamedMechanism", "lint", "Finding", "finding_lines"]
