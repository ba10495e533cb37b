"""Kinematics: solving a mechanism's motion.

* :mod:`.plan` which links are found from which, in what order (structure);
* :mod:`.geometry`, :mod:`.closed_form` single links and dyads in closed form;
* :mod:`.equations`, :mod:`.groups` the constraint equations, and groups of higher
  class by Newton's method with continuation;
* :mod:`.tracking` positions along a path of input values, assembly modes kept;
* :mod:`.rates` exact velocities and accelerations;
* :mod:`.sweep` the input's cycle and the sweep; :mod:`.columns` the CSV's columns;
* :mod:`.summary` stroke, time ratio, extremes, dead centres;
* :mod:`.motion` :func:`solve` and the :class:`Motion` it returns (results).
"""

from chaingraph.kinematics.motion import (
    Motion,
    full_turns,
    full_turns_cost,
    full_turns_drivers,
    solve,
)
from chaingraph.kinematics.plan import Plan, build_plan
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
           "output_signal", "OutputSignal"]
