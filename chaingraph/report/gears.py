"""The report's gear trains: which entries are trains, their speeds worked out as the
textbook tabulates them, and their section of the entry page.

A gear train's page has no skeleton and no animation (a skeleton of links turning about
one axis is no picture of a train): it has the train's drawing
(:func:`~chaingraph.drawing.gears.train_svg`, the front view and the graph of turning
and gear pairs), its kind, and its speeds by the tabular method with the ratios. A train
of one degree of freedom (with its fixed link at rest) is driven by its first moving link
at 1 rpm, so that the speeds are ratios to it; a train of two (an epicyclic train in its
housing, a differential) is shown as the textbook's table shows it: each member that
turns in the fixed link held in turn (a brake), another driven at 1 rpm.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from fractions import Fraction

from chaingraph.errors import ChainGraphError
from chaingraph.kinematics.gears import TrainSpeeds, train_kind, train_speeds
from chaingraph.model.chain import Chain

__all__ = ["train_fixed", "TrainWay", "train_ways", "gears_section"]


def train_fixed(chain: Chain) -> str:
    """The link a gear train's page holds at rest: its ``[mechanism]``'s fixed link,
    else the link the file names first (the catalog's trains name their frame first)."""
    m = chain.mechanism
    return m.fixed if m is not None and m.fixed is not None else chain.links[0]


@dataclass(frozen=True)
class TrainWay:
    """One way of running a train: ``held`` (a link held at rest besides the fixed one,
    or None) and ``driver`` (turned at 1 rpm), with the speeds that follow."""

    held: str | None
    driver: str
    result: TrainSpeeds

    @property
    def kind(self) -> str:
        """The train's kind as it runs this way: with the held link at rest too (the
        epicyclic train with its arm held is an ordinary one)."""
        return train_kind(self.result.train, self.held) if self.held else self.result.kind


def _members(chain: Chain, fixed: str) -> list[str]:
    """The links that turn in the fixed link (on an R joint with it), in file order."""
    on = {x for j in chain.joints if j.kind == "R" and fixed in j.links for x in j.links}
    return [x for x in chain.links if x in on and x != fixed]


def _run(chain: Chain, fixed: str, speeds: dict[str, int]) -> TrainSpeeds | None:
    try:
        return train_speeds(chain, fixed=fixed, speeds=speeds)
    except ChainGraphError:
        return None


def train_ways(chain: Chain, *, fixed: str | None = None) -> list[TrainWay]:
    """The ways the report runs a gear train with ``fixed`` at rest (by default
    :func:`train_fixed`): driven by its first moving link that gives it one motion,
    or, when one speed does not settle it, each member turning in the fixed link held
    in turn with the first other link that then drives it at 1 rpm (a held member and
    a driver that the gears tie together, or that leave a freedom over, are skipped).
    Empty when no such way settles the train.

    Examples
    --------
    >>> from chaingraph.naming.catalog import catalog_path
    >>> from chaingraph.files import load
    >>> ways = train_ways(load(catalog_path("epicyclic-gear-train")))
    >>> [(w.held, w.driver, str(w.result.speeds["arm"])) for w in ways]
    [('sun', 'annulus', '4/5'), ('annulus', 'sun', '1/5'), ('arm', 'sun', '0')]
    """
    fixed = fixed if fixed is not None else train_fixed(chain)
    moving = [x for x in chain.links if x != fixed]
    for driver in moving:
        result = _run(chain, fixed, {driver: 1})
        if result is not None:
            return [TrainWay(None, driver, result)]
    ways = []
    for held in _members(chain, fixed):
        for driver in moving:
            result = _run(chain, fixed, {held: 0, driver: 1}) if driver != held else None
            if result is not None:
                ways.append(TrainWay(held, driver, result))
                break
    return ways


# -- the page's section ----------------------------------------------------------------
def _esc(x: object) -> str:
    return html.escape(str(x))


def _shown(value: Fraction | None) -> str:
    """A speed or ratio: exact when short, else to 6 figures; a dash for none."""
    if value is None:
        return "–"
    exact = str(value)
    return exact if len(exact) <= 12 else f"{float(value):.6g}"


def _way_title(fixed: str, way: TrainWay) -> str:
    held = f", {way.held} held" if way.held else ""
    return f"{fixed} fixed{held}, {way.driver} at 1 rpm"


def _speeds_table(chain: Chain, fixed: str, ways: list[TrainWay]) -> list[str]:
    """Every way's speeds in one table, a row per way, a column per link."""
    links = list(chain.links)
    out = ["<table id=\"gear-speeds\"><tr><th>held</th><th>driver (1 rpm)</th>"
           "<th>kind, so held</th>"
           + "".join(f"<th>{_esc(x)}</th>" for x in links) + "</tr>"]
    for w in ways:
        out.append(f"<tr><td>{_esc(w.held or fixed)}</td><td>{_esc(w.driver)}</td>"
                   f"<td>{_esc(w.kind)}</td>"
                   + "".join(f"<td class=\"num\">{_esc(_shown(w.result.speeds[x]))}</td>"
                             for x in links) + "</tr>")
    out.append("</table>")
    return out


def _ratios_table(way: TrainWay) -> list[str]:
    """The driver's speed over each other moving link's: the train's ratios."""
    r = way.result
    moving = [x for x in r.train.links if r.speeds[x] != 0 and x != way.driver]
    out = ["<table class=\"gear-ratios\"><tr><th>ratio</th><th>value</th>"
           "<th>decimal</th></tr>"]
    for x in moving:
        value = r.ratio(way.driver, x)
        out.append(f"<tr><td>{_esc(way.driver)} / {_esc(x)}</td><td class=\"num\">"
                   f"{_esc(_shown(value))}</td><td class=\"num\">"
                   f"{float(value or 0):.6g}</td></tr>")
    out.append("</table>")
    return out


def _tabular_table(way: TrainWay) -> list[str]:
    """The tabular method's rows: each carrier held and its first gear turned +1 (the
    products of the teeth), times x, all turned y with the carrier."""
    out = ["<table class=\"gear-tabular\"><tr><th>carrier</th><th>x</th><th>y</th>"
           "<th>gear</th><th>+1 turn</th><th>y + x r</th></tr>"]
    for row in way.result.table:
        for k, (gear, r) in enumerate(row.ratios):
            head = (f"<td rowspan=\"{len(row.ratios)}\">{_esc(row.carrier)}</td>"
                    f"<td rowspan=\"{len(row.ratios)}\" class=\"num\">{_esc(_shown(row.x))}"
                    f"</td><td rowspan=\"{len(row.ratios)}\" class=\"num\">"
                    f"{_esc(_shown(row.y))}</td>") if k == 0 else ""
            out.append(f"<tr>{head}<td>{_esc(gear)}</td><td class=\"num\">{_esc(_shown(r))}"
                       f"</td><td class=\"num\">{_esc(_shown(row.y + row.x * r))}</td></tr>")
    out.append("</table>")
    return out


def gears_section(chain: Chain, slug: str, fixed: str, ways: list[TrainWay]) -> list[str]:
    """The HTML of a gear train's section: its drawing (``img/SLUG-train.svg``), its
    kind, the speeds of every way it is run, the ratios and the tabular method's rows."""
    teeth = ", ".join(f"{g.links[0]}-{g.links[1]} {g.teeth[0]}:{g.teeth[1]}"
                      f"{' (internal)' if g.internal else ''} on {g.carrier}"
                      for g in chain.gears)
    out = ["<h2>The gear train</h2><div class=\"figures\">",
           f"<figure><img src=\"img/{_esc(slug)}-train.svg\" alt=\"the gear train "
           f"{_esc(chain.name)}\" width=\"760\"><figcaption>The train as the textbook draws "
           "it: each gear its pitch circle about its axis (an annulus a ring), a moving "
           f"carrier an arm through the axes it holds, {_esc(fixed)}'s bearings hatched; "
           "beside it the graph of turning pairs (thin) and gear pairs (thick, marked "
           "with their carrier).</figcaption></figure></div>",
           f"<p><b>Gear pairs:</b> {_esc(teeth)}.</p>"]
    if not ways:
        return out
    freedom = ways[0].result.freedom
    out.append(f"<p><b>Kind:</b> {_esc(ways[0].result.kind)}, {freedom} degree"
               f"{'' if freedom == 1 else 's'} of freedom with {_esc(fixed)} fixed. "
               "Speeds in rpm with the driver at 1 rpm (so they are ratios to it), "
               "exact, by the tabular method and the relative-velocity (Willis) equations, "
               "which agree; <code>chaingraph gears</code> gives them for any speeds.</p>")
    out.append("<h3>Speeds</h3>")
    out += _speeds_table(chain, fixed, ways)
    for w in ways:
        out.append(f"<h3>{_esc(_way_title(fixed, w))}</h3><div class=\"figures\"><div>"
                   "<p>Ratios (the driver's speed over each link's):</p>")
        out += _ratios_table(w)
        out.append("</div><div><p>Tabular method (carrier held, first gear +1 turn; "
                   "times x; all turned y with the carrier):</p>")
        out += _tabular_table(w)
        out.append("</div></div>")
    return out
