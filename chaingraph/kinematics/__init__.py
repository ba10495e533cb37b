"""Kinematics: solving a mechanism's motion.

* :mod:`.plan` which links are found from which, in what order (structure);
* :mod:`.geometry`, :mod:`.closed_form` single links and dyads in closed form;
* :mod:`.equations`, :mod:`.groups` the constraint equations, and groups of higher
  class by Newton's method with continuation;
* :mod:`.tracking` positions along a path of input values, assembly modes kept;
* :mod:`.rates` exact velocities and accelerations;
* :mod:`.inputs` the one front door for the inputs: chosen and checked once, for a
  sweep and for one pose alike (a :class:`Drive`);
* :mod:`.sweep` the input's cycle and the sweep; :mod:`.columns` a sweep's typed arrays
  (:class:`LinkMotion`, :class:`PointMotion`, :class:`SlideMotion`) and the CSV's
  columns as their view;
* :mod:`.summary` stroke, time ratio, extremes, dead centres;
* :mod:`.motion` :func:`solve` and the :class:`Motion` it returns (results);
* :mod:`.pose` :func:`pose_motion`: the mechanism at one input value (a
  :class:`PoseMotion` of :class:`LinkState` items);
* :mod:`.assembly` a file given by lengths assembled (:func:`assemble`), a drawn one
  measured (:func:`measure`);
* :mod:`.behaviour` which links turn fully (Grashof's categories and beyond); its
  function ``behaviour`` keeps its module's name, so it is not offered here.
"""

from chaingraph.kinematics.assembly import Assembly, assemble, measure, measured_document
from chaingraph.kinematics.behaviour import behaviour_cost, behaviour_key, turning_links
from chaingraph.kinematics.columns import LinkMotion, LinkStates, PointMotion, SlideMotion
from chaingraph.kinematics.inputs import Drive, pose_drive, sweep_drive
from chaingraph.kinematics.motion import (
    Motion,
    full_turns,
    full_turns_cost,
    full_turns_drivers,
    solve,
)
from chaingraph.kinematics.plan import Plan, build_plan
from chaingraph.kinematics.pose import LinkState, PoseMotion, pose_motion
from chaingraph.kinematics.summary import (
    ExtremePosition,
    OutputSignal,
    Summary,
    output_signal,
    path_direction,
    summary_rows,
)
from chaingraph.kinematics.sweep import Cycle, cycle, feasible_range

__all__ = ["Motion", "LinkMotion", "PointMotion", "SlideMotion", "LinkStates", "Drive",
           "sweep_drive", "pose_drive", "PoseMotion", "LinkState", "pose_motion", "Plan",
           "Cycle", "solve", "build_plan", "cycle", "feasible_range", "full_turns",
           "full_turns_cost", "full_turns_drivers", "Summary", "ExtremePosition",
           "summary_rows", "path_direction", "output_signal", "OutputSignal", "assemble",
           "measure", "measured_document", "Assembly", "turning_links", "behaviour_key",
           "behaviour_cost"]
