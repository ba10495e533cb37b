"""chaingraph: planar kinematic chains as link-joint graphs.

Load a chain file, classify it, and (in later modules) enumerate its inversions,
solve its motion and draw it.

>>> import chaingraph
>>> from chaingraph.naming.catalog import catalog_path
>>> chain = chaingraph.load(catalog_path("four-bar-chain"))
>>> chaingraph.classify(chain).verdict
'kinematic chain'
"""

from chaingraph.synthesis import design
from chaingraph.kinematics.assembly import measure
from chaingraph.drawing.notebook import animate
from chaingraph.structure.atlas import atlas
from chaingraph.model.chain import Chain, Input, Joint, Mechanism, Point
from chaingraph.files import dumps, from_document, load, loads, save
from chaingraph.structure.classify import Check, Classification, classify
from chaingraph.errors import (AssemblyError, AtlasRunError, AtlasSizeError, ChainFileError,
                     ChainGraphError,
                     ChainGraphWarning, ChainStructureError, DesignError, DimensionError,
                     MechanismError, PoseAdjustedWarning)
from chaingraph.graphical import instant_centres, velocity_polygon
from chaingraph.graphical.centres import InstantCentres
from chaingraph.graphical.polygons import Polygons
from chaingraph.naming.identify import Identification, identify
from chaingraph.naming.inversions import Inversion, Inversions, inversions
from chaingraph.structure.isomorphism import automorphism_orbits, canonical_form, is_isomorphic, isomorphism
from chaingraph.kinematics import Motion, feasible_range, solve
from chaingraph.kinematics import Plan, build_plan
from chaingraph.structure.rigidity import rigid_subchains

__version__ = "0.1.0"

#: the results a notebook displays richly (:func:`chaingraph.drawing.notebook.register`)
RESULTS = (Chain, Classification, Inversions, Motion, InstantCentres, Polygons)

if "IPython" in __import__("sys").modules:        # in a notebook: its rich displays
    from chaingraph.drawing.notebook import register as _register_displays
    _register_displays(RESULTS)

__all__ = [
    "Chain", "Joint", "Mechanism", "Point", "Input",
    "load", "loads", "from_document", "dumps", "save",
    "classify", "Classification", "Check", "rigid_subchains",
    "inversions", "Inversions", "Inversion", "identify", "Identification",
    "canonical_form", "is_isomorphic", "isomorphism", "automorphism_orbits",
    "atlas", "design", "solve", "instant_centres", "velocity_polygon", "measure", "animate", "Motion", "feasible_range", "build_plan", "Plan",
    "ChainGraphError", "ChainFileError", "ChainStructureError", "MechanismError",
    "AssemblyError", "AtlasRunError", "AtlasSizeError", "DesignError", "DimensionError",
    "ChainGraphWarning", "PoseAdjustedWarning",
]
