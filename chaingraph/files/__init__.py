"""Load and save: chain files in and out, and the models of other tools brought in and
sent out.

* :mod:`.native` chaingraph's own TOML chain files: :func:`load`, :func:`loads`,
  :func:`save`, :func:`dumps`, and :func:`place` (a read file in its drawn pose);
* :mod:`.pylinkage` pylinkage 1.3's JSON serialisation of a mechanism:
  :func:`read_pylinkage`, :func:`pylinkage_json`;
* :mod:`.pyslvs` Pyslvs's mechanism expression: :func:`read_pyslvs`,
  :func:`pyslvs_expression`;
* :mod:`.peers` :func:`read_model`: a model from its file, whichever tool wrote it;
* :mod:`.imported` an imported model (:class:`Imported`: the chain file and what could
  not be carried over) and the refusal of a model a format cannot hold
  (:class:`~chaingraph.errors.InterchangeError`).
"""

from chaingraph.files.imported import Imported, model_kind, model_text
from chaingraph.files.native import (
    dumps,
    from_document,
    load,
    loads,
    place,
    read_document,
    read_file,
    read_text,
    save,
)
from chaingraph.files.pylinkage import pylinkage_json, read_pylinkage
from chaingraph.files.peers import read_model
from chaingraph.files.pyslvs import pyslvs_expression, read_pyslvs

__all__ = ["load", "loads", "from_document", "dumps", "save", "read_file", "read_text",
           "read_document", "place", "Imported", "read_pylinkage", "pylinkage_json",
           "read_pyslvs", "pyslvs_expression", "model_kind", "model_text", "read_model"]
