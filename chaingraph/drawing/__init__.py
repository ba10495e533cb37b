"""Pictures: the mechanism in the textbook's style (SVG), plots and drawings through
matplotlib, the link-joint graph, the graphical constructions, the forces, and notebook
displays. matplotlib is imported by the functions that draw with it, when they run.

* :mod:`.scene` one scene for every drawing: shapes in the mechanism's coordinates,
  written as SVG (:func:`svg_elements`) or drawn with matplotlib (:func:`draw_shapes`);
* :mod:`.mechanism` the mechanism at a pose or animated (:func:`mechanism_svg`), the
  chain's skeleton (:func:`skeleton_svg`);
* :mod:`.plots` the motion's plots and the mechanism through matplotlib;
* :mod:`.constructions` instant centres and polygons drawn;
* :mod:`.limits` where an input stops; :mod:`.forces` free bodies, the force polygon,
  the turning moment; :mod:`.graph` the link-joint graph;
* :mod:`.notebook` rich displays of the results and :func:`animate`;
* :mod:`.outlines` each link as a part to cut (:func:`link_outlines`), as DXF or SVG.
"""

from chaingraph.drawing.constructions import draw_centres, draw_polygons
from chaingraph.drawing.forces import (
    force_polygon_shapes,
    force_polygon_svg,
    free_body_shapes,
    free_body_svg,
    plot_shaking,
    plot_turning_moment,
)
from chaingraph.drawing.graph import draw_link_joint_graph
from chaingraph.drawing.limits import limit_motion, limit_shapes, limits_svg
from chaingraph.drawing.mechanism import frame_steps, mechanism_svg, skeleton_svg
from chaingraph.drawing.notebook import Animation, animate, figure_svg, register
from chaingraph.drawing.outlines import Outlines, link_outlines, outlines_dxf, outlines_svg
from chaingraph.drawing.plots import draw_mechanism, output_series, plot_motion, plot_variation
from chaingraph.drawing.scene import (
    Scene,
    Shape,
    View,
    draw_shapes,
    svg_document,
    svg_elements,
)

__all__ = ["mechanism_svg", "skeleton_svg", "frame_steps", "plot_motion", "draw_mechanism",
           "plot_variation", "output_series", "draw_centres", "draw_polygons", "limits_svg",
           "limit_shapes", "limit_motion", "free_body_svg", "force_polygon_svg",
           "free_body_shapes", "force_polygon_shapes", "plot_turning_moment",
           "plot_shaking",
           "draw_link_joint_graph", "Scene", "Shape", "View", "svg_document",
           "svg_elements", "draw_shapes", "animate", "Animation", "figure_svg", "register",
           "Outlines", "link_outlines", "outlines_dxf", "outlines_svg"]
