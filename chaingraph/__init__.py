"""chaingraph: planar kinematic chains as link-joint graphs.

Load a chain file, classify it, enumerate and name its inversions, solve its motion and
its forces, draw it; the atlas of every chain of N links; the design of quick-return
drives. Each subpackage's face (``chaingraph.kinematics``, ``chaingraph.naming`` ...)
offers the rest of its names.

>>> import chaingraph
>>> chain = chaingraph.load(chaingraph.catalog_path("four-bar-chain"))
>>> chaingraph.classify(chain).verdict
'kinematic chain'
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, Any

from chaingraph._util.lazy import lazy_attribute
from chaingraph._util.memory import keep_freed_memory

keep_freed_memory()             # a sweep's arrays reuse the heap (see chaingraph._util.memory)

from chaingraph.dynamics import PoseForces, SweepForces, forces
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
from chaingraph.files import dumps, from_document, load, loads, save
from chaingraph.graphical import InstantCentres, Polygons, instant_centres, velocity_polygon
from chaingraph.kinematics import (
    Motion,
    Plan,
    PoseMotion,
    Summary,
    build_plan,
    feasible_range,
    measure,
    pose_motion,
    solve,
)
from chaingraph.model import Chain, Input, Joint, LinkMass, Load, Mechanism, Point
from chaingraph.naming import (
    Identification,
    Inversion,
    Inversions,
    catalog_path,
    identify,
    inversions,
)
from chaingraph.structure import Check, Classification, classify, rigid_subchains
from chaingraph.structure.isomorphism import (
    automorphism_orbits,
    canonical_form,
    is_isomorphic,
    isomorphism,
)
from chaingraph.variation import Variation, vary

if TYPE_CHECKING:
    from chaingraph import synthesis
    from chaingraph.drawing.notebook import animate
    from chaingraph.structure.atlas import Atlas, atlas
    from chaingraph.synthesis import design

__version__ = "0.1.0"

#: the results a notebook displays richly (:func:`chaingraph.drawing.notebook.register`)
RESULTS = (Chain, Classification, Inversions, Motion, InstantCentres, Polygons, PoseForces,
           SweepForces)

# loaded when first used, so that `import chaingraph` loads neither the atlas (nor
# pynauty) nor the drawing modules: name -> (module, attribute or None for the module)
_LAZY: dict[str, tuple[str, str | None]] = {
    "atlas": ("chaingraph.structure.atlas", "atlas"),
    "Atlas": ("chaingraph.structure.atlas", "Atlas"),
    "synthesis": ("chaingraph.synthesis", None),
    "design": ("chaingraph.synthesis.design", None),
    "animate": ("chaingraph.drawing.notebook", "animate")}


def __getattr__(name: str) -> Any:
    return lazy_attribute(__name__, _LAZY, name)


if "IPython" in sys.modules:        # in a notebook: its rich displays
    from chaingraph.drawing.notebook import register as _register_displays
    _register_displays(RESULTS)

__all__ = [
    "Chain", "Joint", "Mechanism", "Point", "Input", "LinkMass", "Load",
    "load", "loads", "from_document", "dumps", "save",
    "classify", "Classification", "Check", "rigid_subchains",
    "inversions", "Inversions", "Inversion", "identify", "Identification",
    "canonical_form", "is_isomorphic", "isomorphism", "automorphism_orbits",
    "catalog_path", "solve", "Motion", "Summary", "feasible_range", "build_plan", "Plan",
    "pose_motion", "PoseMotion", "measure", "forces", "PoseForces", "SweepForces",
    "instant_centres", "InstantCentres", "velocity_polygon", "Polygons", "vary",
    "Variation", "atlas", "Atlas", "synthesis", "design", "animate",
    "ChainGraphError", "ChainFileError", "ChainStructureError", "MechanismError",
    "AssemblyError", "AtlasRunError", "AtlasSizeError", "DesignError", "DimensionError",
    "DegenerateDrawingError", "UnboundedRangeError", "ChainGraphWarning", "PoseAdjustedWarning",
]
