"""Dimensional synthesis: from a task to certified mechanisms.

* :func:`function` function generation (four-bar, slider crank), :mod:`.function_generation`;
* :func:`path` path generation (four-bar), :mod:`.path_generation`, by the optimiser of
  :mod:`.optimiser` over a mechanism family of :mod:`.family`; with ``links`` 6 or 8,
  type synthesis over the atlas's chains, :mod:`.type_synthesis`;
* :func:`motion` motion generation (four-bar, slider crank through 2 to 5 poses),
  :mod:`.motion_generation`, on the Burmester geometry of :mod:`.poses` and
  :mod:`.burmester`;
* :mod:`.certification` every candidate written as a chain file, read back, solved by
  chaingraph's own solver and checked (circuit, branch and order defects, the
  transmission angle, the error recomputed);
* :mod:`.result` the :class:`Synthesis` and its :class:`Solution` list, ``to_dict()`` the
  JSON; :mod:`.task` the tasks; :mod:`.expression` a function of x, read safely;
* :mod:`.design` the quick return drives (``slotted_lever``, ``whitworth``).
"""

from chaingraph.synthesis.certification import (
    REASONS,
    Certified,
    FunctionTargets,
    PointTargets,
    PoseTargets,
    Rejected,
    certify,
)
from chaingraph.synthesis.design import KINDS, Design, slotted_lever, whitworth
from chaingraph.synthesis.function_generation import function
from chaingraph.synthesis.type_synthesis import LINKS, check_links, motion, path
from chaingraph.synthesis.result import Curve, Error, Searched, Solution, Synthesis
from chaingraph.synthesis.task import (
    FunctionTask,
    MotionTask,
    PathTask,
    function_task,
    motion_task,
    path_task,
)

__all__ = ["function", "path", "LINKS", "check_links", "motion", "MotionTask", "motion_task", "Synthesis", "Solution", "Error", "Curve", "Searched", "certify",
           "Certified", "Rejected", "FunctionTargets", "PointTargets", "PoseTargets",
           "REASONS", "FunctionTask", "function_task", "PathTask", "path_task", "Design", "slotted_lever",
           "whitworth", "KINDS"]
