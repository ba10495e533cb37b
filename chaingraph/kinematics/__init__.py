"""Kinematics: solving a mechanism's motion.

* :mod:`.plan` which links are found from which, in what order (structure);
* :mod:`.geometry`, :mod:`.closed_form` single links and dyads in closed form;
* :mod:`.equations`, :mod:`.groups` the constraint equations, and groups of higher
  class by Newton's method with continuation;
* :mod:`.tracking` positions along a path of input values, assembly modes kept;
* :mod:`.rates` exact velocities and accelerations;
* :mod:`.sweep` the input's cycle and the sweep; :mod:`.columns` the CSV's columns;
* :mod:`.summary` stroke, time ratio, extremes, dead centres;
* :mod:`.motion` :func:`solve` and the :class:`Motion` it returns (results);
* :mod:`.pose` :func:`pose_motion`, every link's motion at one input value;
* :mod:`.assembly` a file given by lengths assembled (:func:`assemble`), a drawn one
  measured (:func:`measure`);
* :mod:`.behaviour` which links turn fully (Grashof's categories and beyond); its
  function ``behaviour`` keeps its module's name, so it is not offered here.
"""

from chaingraph.kinematics.assembly import Assembly, assemble, measure, measured_document
from chaingraph.kinematics.behaviour import behaviour_cost, behaviour_key, turning_links
from chaingraph.kinematics.motion import (
    Motion,
    full_turns,
    full_turns_cost,
    full_turns_drivers,
    solve,
)
from chaingraph.kinematics.plan import Plan, build_plan
from chaingraph.kinematics.pose import PoseMotion, pose_motion
from chaingraph.kinematics.summary import (
    ExtremePosition,
    OutputSignal,
    Summary,
    output_signal,
    path_direction,
    summary_rows,
)
from chaingraph.kinematics.sweep import Cycle, cycle, feasible_range

__all__ = ["Motion", "Plan", "Cycle", "solve", "build_plan", "cycle", "feasible_range",
           "full_turns", "full_turns_cost", "full_turns_drivers", "Summary", "ExtremePosition", "summary_rows", "path_direction",
           "output_signal", "OutputSignal", "pose_motion", "PoseMotion", "assemble",
           "measure", "measured_document", "Assembly", "turning_links", "behaviour_key",
           "behaviour_cost"]
