"""Gear pairs: two links in mesh (``[[gears]]`` of a chain file), a higher pair.

A :class:`GearPair` names its two links, their numbers of teeth, whether the second is
an annulus (internal teeth) and its carrier: the link that holds both gears' axes (each
gear turns on it by an R joint, or the carrier is the fixed link, the frame of an
ordinary train). The chain counts each gear pair as a joint of kind ``"gear"`` (a higher
pair, H = 1 in Kutzbach's criterion), added to its joints under the pair's id, so that
the structure's counts, graphs and checks see it; the teeth and the carrier are the
pair's own. :func:`gear_pair` reads one table of the file, :func:`check_gears` checks
the pairs against the chain and :func:`gear_entry` writes one back.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from chaingraph.model.values import Fail, shown, type_name

if TYPE_CHECKING:
    from chaingraph.model.chain import Joint

__all__ = ["GearPair", "GEAR_KEYS", "gear_pair", "gear_entry", "check_gears", "pitch_point"]

GEAR_KEYS = ("id", "links", "teeth", "internal", "carrier", "pressure_angle")


@dataclass(frozen=True)
class GearPair:
    """Two links in mesh.

    Attributes
    ----------
    id : str
        The pair's name (shared with the joints' ids).
    links : tuple of str
        The two gears (links); with ``internal``, the second is the annulus.
    teeth : tuple of int
        Their numbers of teeth, in the order of ``links``.
    internal : bool
        True when the second link has internal teeth (an annulus).
    carrier : str
        The link that holds both axes (the frame of an ordinary train, the arm of an
        epicyclic one).
    pressure_angle : float
        The angle (degrees) between the line of action and the common tangent of the
        pitch circles (20 by default): the tooth force's direction in ``forces``.
    """

    id: str
    links: tuple[str, str]
    teeth: tuple[int, int]
    internal: bool = False
    carrier: str = ""
    pressure_angle: float = 20.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "links", tuple(self.links))
        object.__setattr__(self, "teeth", tuple(self.teeth))

    @property
    def sign(self) -> int:
        """The sign of the ratio with the carrier held: -1 external, +1 internal."""
        return 1 if self.internal else -1


def gear_pair(table: dict[str, Any], index: int, fixed: str | None, fail: Fail) -> GearPair:
    """One ``[[gears]]`` table read (types and keys; the chain checks the links).
    ``fixed`` is the file's fixed link, the carrier when none is named."""
    where = f"gear pair #{index + 1}"
    if isinstance(table.get("id"), str) and table["id"]:
        where = f"gear pair {table['id']!r}"
    for key in table:
        if key not in GEAR_KEYS:
            fail(f"unknown key {key!r} (allowed: {', '.join(GEAR_KEYS)})", where)
    for key in ("id", "links", "teeth"):
        if key not in table:
            fail(f"missing required key '{key}'", where)
    if not isinstance(table["id"], str) or not table["id"]:
        fail(f"key 'id' must be a non-empty string, got {shown(table['id'])}", where)
    links = table["links"]
    if (not isinstance(links, list) or len(links) != 2
            or not all(isinstance(x, str) and x for x in links)):
        fail(f"key 'links' must be two link names, got {shown(links)}", where)
    teeth = table["teeth"]
    if (not isinstance(teeth, list) or len(teeth) != 2
            or any(isinstance(z, bool) or not isinstance(z, (int, float))
                   or not 0 < z <= 10**6 or z != int(z) for z in teeth)):
        fail(f"key 'teeth' must be two positive whole numbers of teeth, got {shown(teeth)}",
             where)
    internal = table.get("internal", False)
    if not isinstance(internal, bool):
        fail(f"key 'internal' must be true or false, got {type_name(internal)}", where)
    carrier = table.get("carrier", fixed)
    if carrier is None:
        fail("key 'carrier' is missing and the file has no [mechanism] fixed link to "
             "take for it: name the link that holds both axes", where)
    if not isinstance(carrier, str) or not carrier:
        fail(f"key 'carrier' must be a link name, got {shown(carrier)}", where)
    angle = table.get("pressure_angle", 20.0)
    if isinstance(angle, bool) or not isinstance(angle, (int, float)) or not 0 <= angle < 45:
        fail(f"key 'pressure_angle' must be a number of degrees from 0 to less than 45, got "
             f"{shown(angle)}", where)
    # (the one TOML writer writes numbers as floats: 20.0 teeth are read as 20)
    return GearPair(table["id"], (links[0], links[1]), (int(teeth[0]), int(teeth[1])), internal,
                    carrier, float(angle))


def gear_entry(pair: GearPair) -> dict[str, Any]:
    """A :class:`GearPair` as its ``[[gears]]`` table."""
    out = {"id": pair.id, "links": list(pair.links), "teeth": list(pair.teeth),
           "internal": pair.internal, "carrier": pair.carrier}
    if pair.pressure_angle != 20.0:
        out["pressure_angle"] = pair.pressure_angle
    return out


def check_gears(gears: Sequence[GearPair], turning: Collection[tuple[str, ...]],
                held: Collection[str], fail: Fail) -> None:
    """Every pair's meaning: two distinct links of the chain, teeth positive whole
    numbers, a carrier that holds both axes (each gear turns on it by an R joint, or
    it is the fixed link and each gear turns on that), one pair per id.

    ``turning`` holds the links of each R joint, ``held`` the links that some joint
    other than a gear pair joins (the chain's own links)."""
    seen: set[str] = set()
    for g in gears:
        where = f"gear pair {g.id!r}"
        if g.id in seen:
            fail("the id is given to two gear pairs", where)
        seen.add(g.id)
        a, b = g.links
        if a == b:
            fail(f"key 'links' names one link twice ({a!r}): a gear pair is two links",
                 where)
        for link in g.links:
            if link not in held:
                fail(f"key 'links' names no link of the chain: {link!r} (a gear turns "
                     "on an R joint of the chain)", where)
        if any(isinstance(z, bool) or not isinstance(z, int) or z <= 0 for z in g.teeth):
            fail(f"key 'teeth' must be two positive whole numbers, got {list(g.teeth)}",
                 where)
        if g.carrier not in held:
            fail(f"key 'carrier' names no link of the chain: {g.carrier!r}", where)
        if g.carrier in g.links:
            fail(f"key 'carrier' is one of the gears ({g.carrier!r}): the carrier holds "
                 "the two gears' axes", where)
        for link in g.links:
            if not any(link in r and g.carrier in r for r in turning):
                fail(f"key 'carrier' {g.carrier!r} does not hold the axis of {link!r}: "
                     f"no R joint joins them", where)


def pitch_point(pair: GearPair, joints: Sequence[Joint]) -> tuple[float, float] | None:
    """Where the pair's pitch circles touch in the drawn pose: on the line of the two
    axes (the places of the R joints that join each gear to the carrier), at the first
    gear's pitch radius from its axis (the teeth in proportion: one module); None when
    an axis is not drawn or both are at one place.

    >>> from chaingraph.model.chain import Joint
    >>> axes = [Joint("O", "R", ("arm", "sun", "annulus"), at=(0.0, 0.0)),
    ...         Joint("P", "R", ("arm", "planet"), at=(50.0, 0.0))]
    >>> pitch_point(GearPair("G1", ("sun", "planet"), (20, 30), False, "arm"), axes)
    (20.0, 0.0)
    >>> pitch_point(GearPair("G2", ("planet", "annulus"), (30, 80), True, "arm"), axes)
    (80.0, 0.0)
    """
    def axis(link: str) -> tuple[float, float] | None:
        return next((j.at for j in joints if j.kind == "R" and link in j.links
                     and pair.carrier in j.links), None)
    a, b = axis(pair.links[0]), axis(pair.links[1])
    za, zb = pair.teeth
    if a is None or b is None or a == b or (pair.internal and za == zb):
        return None
    if pair.internal:                  # beyond the pinion, at the annulus's radius from b
        t = zb / (zb - za)
        return (b[0] + (a[0] - b[0]) * t, b[1] + (a[1] - b[1]) * t)
    t = za / (za + zb)
    return (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t)
