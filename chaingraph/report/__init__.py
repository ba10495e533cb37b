"""The HTML report: a page per chain file with its pictures, classification,
inversions, motion and forces (:mod:`.build`), a gear train's drawing and speeds
(:mod:`.gears`), the animation of an inversion
(:mod:`.animation`), and the atlas's illustrated pages and index (:mod:`.atlas`,
:mod:`.atlas_index`; loaded when first used: the atlas loads pynauty).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from chaingraph._util.lazy import lazy_attribute
from chaingraph.report.animation import animate_inversion
from chaingraph.report.build import Report, build_report, chain_paths

if TYPE_CHECKING:
    from chaingraph.report.atlas import (
        IllustratedPage,
        animated_by_default,
        animation_seconds,
        write_illustrated,
    )

#: loaded when first used: name -> (module, attribute)
_LAZY: dict[str, tuple[str, str | None]] = {
    name: ("chaingraph.report.atlas", name)
    for name in ("write_illustrated", "IllustratedPage", "animated_by_default",
                 "animation_seconds")}


def __getattr__(name: str) -> Any:
    return lazy_attribute(__name__, _LAZY, name)


__all__ = ["build_report", "Report", "chain_paths", "animate_inversion",
           "write_illustrated", "IllustratedPage", "animated_by_default",
           "animation_seconds"]
