"""Forces: the joints' reactions and the inputs' efforts, static and kinetostatic
(:func:`forces`), from the motion the kinematics solves.

* :mod:`.reactions` :func:`forces` and its results, :class:`PoseForces` at one pose
  and :class:`SweepForces` over a sweep;
* :mod:`.equilibrium` the equations of every link's equilibrium, solved at each pose,
  with the loads as the motion has them there;
* :mod:`.cycle` the integrals over the input's cycle (the mean effort, the steady mean
  torque, the energy fluctuation), exact rather than on the sweep's grid.
"""

from chaingraph.dynamics.reactions import (
    AppliedCouple,
    AppliedForce,
    Effort,
    EffortStats,
    Flywheel,
    ForcesSummary,
    PoseForces,
    Reaction,
    SweepForces,
    forces,
)

__all__ = ["forces", "PoseForces", "SweepForces", "Reaction", "Effort", "EffortStats",
           "Flywheel", "ForcesSummary", "AppliedForce", "AppliedCouple"]
