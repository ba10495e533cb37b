"""The textbook's graphical analysis, exact: instantaneous centres (Kennedy's theorem)
and velocity and acceleration polygons at one input value.

* :mod:`.pose` the mechanism solved at one input value, every link's motion;
* :mod:`.centres` the instantaneous centres and the velocities through them;
* :mod:`.polygons` the velocity and acceleration polygons (images and components);
* :mod:`.draw` their pictures (matplotlib).
"""

from chaingraph.graphical.centres import Centre, InstantCentres, instant_centres
from chaingraph.graphical.polygons import (
           Component,
           Image,
           Polygons,
           Relative,
           velocity_polygon,
)
from chaingraph.kinematics.pose import LinkState, PoseMotion, pose_motion

__all__ = ["instant_centres", "InstantCentres", "Centre", "velocity_polygon", "Polygons",
           "Image", "Relative", "Component", "pose_motion", "PoseMotion", "LinkState"]
