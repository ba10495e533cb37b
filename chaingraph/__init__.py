"""chaingraph: planar kinematic chains as link-joint graphs.

Load a chain file, classify it, and (in later modules) enumerate its inversions,
solve its motion and draw it.

>>> import chaingraph
>>> from chaingraph.naming.catalog import catalog_path
>>> chain = chaingraph.load(catalog_path("four-bar-chain"))
>>> chaingraph.classify(chain).verdict
'kinematic chain'
"""

import importlib

from chaingraph.errors import (
    AssemblyError,
    AtlasRunError,
    AtlasSizeError,
    ChainFileError,
    ChainGraphError,
    ChainGraphWarning,
    ChainStructureError,
    DegenerateDrawingError,
    DesignError,
    DimensionError,
    MechanismError,
    PoseAdjustedWarning,
    UnboundedRangeError,
)
from chaingraph.dynamics import PoseForces, SweepForces, forces
from chaingraph.files import dumps, from_document, load, loads, save
from chaingraph.graphical import instant_centres, velocity_polygon
from chaingraph.graphical.centres import InstantCentres
from chaingraph.graphical.polygons import Polygons
from chaingraph.kinematics import (
    Motion,
    Plan,
    Summary,
    build_plan,
    feasible_range,
    solve,
)
from chaingraph.kinematics.assembly import measure
from chaingraph.model.chain import Chain, Input, Joint, LinkMass, Load, Mechanism, Point
from chaingraph.naming.identify import Identification, identify
from chaingraph.naming.inversions import Inversion, Inversions, inversions
from chaingraph.structure.classify import Check, Classification, classify
from chaingraph.structure.isomorphism import (
    automorphism_orbits,
    canonical_form,
    is_isomorphic,
    isomorphism,
)
from chaingraph.structure.rigidity import rigid_subchains
from chaingraph.variation import Variation, vary

__version__ = "0.1.0"

#: the results a notebook displays richly (:func:`chaingraph.drawing.notebook.register`)
RESULTS = (Chain, Classification, Inversions, Motion, InstantCentres, Polygons, PoseForces,
           SweepForces)

# loaded when first used, so that `import chaingraph` loads neither the atlas (nor
# pynauty) nor the drawing modules: name -> (module, attribute or None for the module)
_LAZY = {"atlas": ("chaingraph.structure.atlas", "atlas"),
         "design": ("chaingraph.synthesis.design", None),
         "synthesis": ("chaingraph.synthesis", None),
         "animate": ("chaingraph.drawing.notebook", "animate")}


def __getattr__(name):
    if name in _LAZY:
        module, attribute = _LAZY[name]
        value = importlib.import_module(module)
        value = getattr(value, attribute) if attribute else value
        globals()[name] = value
        return value
    raise AttributeError(f"module 'chaingraph' has no attribute {name!r}")


if "IPython" in __import__("sys").modules:        # in a notebook: its rich displays
    from chaingraph.drawing.notebook import register as _register_displays
    _register_displays(RESULTS)

__all__ = [
    "Chain", "Joint", "Mechanism", "Point", "Input", "LinkMass", "Load",
    "load", "loads", "from_document", "dumps", "save",
    "classify", "Classification", "Check", "rigid_subchains",
    "inversions", "Inversions", "Inversion", "identify", "Identification",
    "canonical_form", "is_isomorphic", "isomorphism", "automorphism_orbits",
    "atlas", "design", "solve", "forces", "PoseForces", "SweepForces", "vary", "Variation", "instant_centres", "velocity_polygon", "measure", "animate", "Motion", "Summary", "feasible_range", "build_plan", "Plan",
    "ChainGraphError", "ChainFileError", "ChainStructureError", "MechanismError",
    "AssemblyError", "AtlasRunError", "AtlasSizeError", "DesignError", "DimensionError",
    "DegenerateDrawingError", "UnboundedRangeError", "ChainGraphWarning", "PoseAdjustedWarning",
]
