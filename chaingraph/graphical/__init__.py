"""The textbook's graphical analysis, exact: instantaneous centres (Kennedy's theorem)
and velocity and acceleration polygons at one input value.

* :func:`pose_motion` (from :mod:`chaingraph.kinematics.pose`) the mechanism solved at
  one input value, every link's motion;
* :mod:`.centres` the instantaneous centres and the velocities through them
  (:func:`instant_centres`; :func:`centres_of` from a solved pose);
* :mod:`.polygons` the velocity and acceleration polygons, images and components
  (:func:`velocity_polygon`; :func:`polygons_of` from a solved pose);
* their pictures are :mod:`chaingraph.drawing.constructions`.
"""

from chaingraph.graphical.centres import Centre, InstantCentres, centres_of, instant_centres
from chaingraph.graphical.polygons import (
    Component,
    Image,
    Polygons,
    Relative,
    polygons_of,
    velocity_polygon,
)
from chaingraph.kinematics.pose import LinkState, PoseMotion, pose_motion

__all__ = ["instant_centres", "InstantCentres", "Centre", "centres_of", "velocity_polygon",
           "Polygons", "Image", "Relative", "Component", "polygons_of", "pose_motion",
           "PoseMotion", "LinkState"]
