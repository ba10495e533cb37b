"""Joint kinds: the textbook's kinematic pairs and how they are classified.

A kinematic pair is classified by the relative motion it allows (turning, sliding,
rolling, screw, spherical...), by its contact (surface contact: lower pair; line or
point contact: higher pair), by its closure (held mechanically: closed pair; held by
gravity or a spring: unclosed pair) and by the freedom it leaves between its two links,
in plane motion and in space.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PairKind", "PAIR_KINDS", "pair_kind"]


@dataclass(frozen=True)
class PairKind:
    """One kind of kinematic pair (joint).

    Attributes
    ----------
    kind : str
        The key used in chain files (``"R"``, ``"P"``, ``"cam"``...).
    name : str
        The textbook's name, e.g. ``"turning pair"``.
    motion : str
        The relative motion: ``"turning"``, ``"sliding"``, ``"rolling"``...
    contact : str
        ``"lower"`` (surface contact) or ``"higher"`` (line or point contact).
    planar_freedom, spatial_freedom : int or None
        Relative degrees of freedom the pair leaves in plane motion and in space;
        None where the pair has no such form.
    """

    kind: str
    name: str
    motion: str
    contact: str
    planar_freedom: int | None
    spatial_freedom: int | None
    example: str

    @property
    def lower(self) -> bool:
        """True for a lower pair (surface contact)."""
        return self.contact == "lower"

    def freedom(self, space: str) -> int | None:
        """Relative freedom in ``"planar"`` or ``"spatial"`` motion."""
        return self.planar_freedom if space == "planar" else self.spatial_freedom


PAIR_KINDS: dict[str, PairKind] = {
    p.kind: p
    for p in (
        PairKind("R", "turning pair", "turning", "lower", 1, 1, "shaft in a bearing"),
        PairKind("P", "sliding pair", "sliding", "lower", 1, 1, "piston in a cylinder"),
        PairKind("screw", "screw pair", "screw", "lower", None, 1, "bolt and nut"),
        PairKind("cylindrical", "cylindrical pair", "turning and sliding", "lower",
                 None, 2, "round bar in a round hole"),
        PairKind("spherical", "spherical pair", "spherical", "lower", None, 3,
                 "ball and socket joint"),
        PairKind("planar", "planar pair", "plane sliding", "lower", None, 3,
                 "block on a flat table"),
        PairKind("rolling", "rolling pair", "rolling", "higher", 1, None,
                 "wheel rolling on a rail"),
        PairKind("cam", "cam pair", "rolling and sliding", "higher", 2, None,
                 "cam and follower"),
        PairKind("gear", "gear pair", "rolling and sliding", "higher", 2, None,
                 "meshing gear teeth"),
    )
}


def pair_kind(kind: str) -> PairKind:
    """The :class:`PairKind` for a joint kind key.

    Examples
    --------
    >>> pair_kind("R").name
    'turning pair'
    >>> pair_kind("cam").contact, pair_kind("cam").planar_freedom
    ('higher', 2)
    """
    return PAIR_KINDS[kind]
