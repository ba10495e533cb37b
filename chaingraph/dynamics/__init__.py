"""Forces: the joints' reactions and the inputs' efforts, static and kinetostatic
(:func:`forces`), from the motion the kinematics solves."""

from chaingraph.dynamics.reactions import (
    Effort,
    EffortStats,
    ForcesSummary,
    PoseForces,
    Reaction,
    SweepForces,
    forces,
)

__all__ = ["forces", "PoseForces", "SweepForces", "Reaction", "Effort", "EffortStats",
           "ForcesSummary"]
