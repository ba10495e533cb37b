"""Gear trains: the speed of every link, by two independent computations.

A gear train is a chain whose links turn about axes held by R joints and mesh in gear
pairs (:class:`~chaingraph.model.gears.GearPair`, ``[[gears]]``). Its graph has the links
as vertices and two kinds of edge: the turning pairs (R joints) and the gear pairs, each
with its carrier, the link that holds both axes (Buchsbaum and Freudenstein's graph).

The speeds are found twice:

* :func:`willis_speeds`: the relative-velocity (Willis) equation of every gear pair,
  ``(w_a - w_c) / (w_b - w_c) = -+ z_b / z_a`` (minus for external teeth, plus for an
  annulus), with the fixed link at rest and the given speeds, as one linear system
  solved exactly in rationals (the teeth are whole numbers);
* :func:`tabular_speeds`: the textbook's tabular method. For each carrier and each train
  of gears it holds, the carrier is held and one gear turned +1: every gear of that
  train turns by the product of the teeth along the way (the table's first row); the
  row is multiplied by ``x`` and the whole train turned with the carrier by ``y``, so
  every gear turns at ``y + x r``; the unknowns ``x`` and ``y`` come from the fixed link
  and the given speeds.

:func:`train_speeds` runs both and refuses to answer when they disagree; it also names
the train's kind (:func:`train_kind`) and gives the ratio between any two links.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

from chaingraph.errors import AssemblyError, MechanismError
from chaingraph.model.chain import Chain
from chaingraph.model.gears import GearPair

__all__ = ["GearTrain", "TrainSpeeds", "TableRow", "gear_train", "is_gear_train", "train_kind",
           "willis_speeds", "tabular_speeds", "train_speeds", "solve_exact"]

KINDS = ("simple", "compound", "reverted", "epicyclic")


@dataclass(frozen=True)
class GearTrain:
    """A gear train's graph: ``links`` (vertices), ``turning`` (the R joints' pairs of
    links, one per joint equivalent) and ``gears`` (the gear pairs with their
    carriers)."""

    name: str
    links: tuple[str, ...]
    turning: tuple[tuple[str, str], ...]
    gears: tuple[GearPair, ...]
    axes: tuple[tuple[str, ...], ...] = ()    # the links on each R joint (one axis)

    def coaxial(self, a: str, b: str) -> bool:
        """True when one R joint holds both links (they turn about one axis)."""
        return any(a in axis and b in axis for axis in self.axes)

    def graph(self) -> dict[str, list]:
        """The graph as the contract's JSON writes it: ``links``, ``turning`` [[a, b]]
        and ``gears`` [[a, b, carrier]]."""
        return {"links": list(self.links), "turning": [list(t) for t in self.turning],
                "gears": [[*g.links, g.carrier] for g in self.gears]}


@dataclass(frozen=True)
class TableRow:
    """One train of the tabular method: ``carrier`` held, ``ratios`` the turns of each
    of its gears when the first turns +1; ``x`` the turns given to the first gear,
    ``y`` the turns of the carrier (so that a gear turns ``y + x * ratio``)."""

    carrier: str
    ratios: tuple[tuple[str, Fraction], ...]
    x: Fraction
    y: Fraction


@dataclass(frozen=True)
class TrainSpeeds:
    """The speeds of a gear train's links (rpm, exact), its fixed link, the speeds
    given, its kind, its degrees of freedom and the tabular method's rows."""

    train: GearTrain
    fixed: str
    given: tuple[tuple[str, Fraction], ...]
    speeds: dict[str, Fraction]
    kind: str
    freedom: int
    table: tuple[TableRow, ...]

    def ratio(self, a: str, b: str) -> Fraction | None:
        """The speed ratio ``w_a / w_b`` (None when ``b`` is at rest)."""
        for link in (a, b):
            if link not in self.speeds:
                raise MechanismError(f"no link {link!r} in the train (links: "
                                     f"{', '.join(self.train.links)})", parameter="ratio")
        return None if self.speeds[b] == 0 else self.speeds[a] / self.speeds[b]


def is_gear_train(chain: Chain) -> bool:
    """Whether ``chain`` is a gear train: it has gear pairs (``[[gears]]``) and its
    turning and sliding pairs close no loop (their joint equivalents are fewer than its
    links), so that its links move only through the gears. A linkage with gears in it
    (a geared five-bar) is not one: the position solver moves it.

    Examples
    --------
    >>> from chaingraph.naming.catalog import catalog_path
    >>> from chaingraph.files import load
    >>> is_gear_train(load(catalog_path("simple-gear-train")))
    True
    >>> is_gear_train(load(catalog_path("four-bar-chain")))
    False
    """
    lower = sum(len(j.links) - 1 for j in chain.joints if j.kind in ("R", "P"))
    return bool(chain.gears) and lower < len(chain.links)


def gear_train(chain: Chain) -> GearTrain:
    """The graph of a chain's gear train (refused when it has no gear pairs)."""
    if not chain.gears:
        raise MechanismError("the chain has no gear pairs ([[gears]])",
                             mechanism=chain.name)
    turning = tuple((j.links[0], other) for j in chain.joints if j.kind == "R"
                    for other in j.links[1:])
    axes = tuple(j.links for j in chain.joints if j.kind == "R")
    return GearTrain(chain.name, chain.links, turning, chain.gears, axes)


def solve_exact(rows: Sequence[Sequence[Fraction]], rhs: Sequence[Fraction], size: int
                ) -> tuple[list[Fraction | None], bool]:
    """Gauss-Jordan elimination in rationals: the unknowns that the equations fix
    (None for those they leave free) and whether the equations agree.

    >>> solve_exact([[Fraction(1), Fraction(1)], [Fraction(1), Fraction(-1)]],
    ...             [Fraction(3), Fraction(1)], 2)
    ([Fraction(2, 1), Fraction(1, 1)], True)
    >>> solve_exact([[Fraction(1), Fraction(1)]], [Fraction(3)], 2)
    ([None, None], True)
    """
    m = [list(r) + [b] for r, b in zip(rows, rhs)]
    pivots: list[int] = []
    r = 0
    for col in range(size):
        k = next((i for i in range(r, len(m)) if m[i][col] != 0), None)
        if k is None:
            continue
        m[r], m[k] = m[k], m[r]
        p = m[r][col]
        m[r] = [v / p for v in m[r]]
        for i in range(len(m)):
            if i != r and m[i][col] != 0:
                f = m[i][col]
                m[i] = [a - f * b for a, b in zip(m[i], m[r])]
        pivots.append(col)
        r += 1
    agree = all(row[-1] == 0 for row in m[r:])
    out: list[Fraction | None] = [None] * size
    for i, col in enumerate(pivots):
        if all(m[i][c] == 0 for c in range(size) if c != col):
            out[col] = m[i][-1]
    return out, agree


def _conditions(links: Sequence[str], fixed: str, given: Mapping[str, Fraction]
                ) -> tuple[list[list[Fraction]], list[Fraction]]:
    """The rows that hold the fixed link at rest and the given links at their speeds."""
    index = {x: i for i, x in enumerate(links)}
    rows, rhs = [], []
    for link, w in [(fixed, Fraction(0)), *given.items()]:
        row = [Fraction(0)] * len(links)
        row[index[link]] = Fraction(1)
        rows.append(row)
        rhs.append(w)
    return rows, rhs


def willis_speeds(train: GearTrain, fixed: str, given: Mapping[str, Fraction]
                  ) -> tuple[list[Fraction | None], bool]:
    """Every link's speed by the Willis equation of each gear pair,
    ``z_a (w_a - w_c) = -+ z_b (w_b - w_c)``, as one linear system (None: a speed the
    conditions leave free; the flag: the conditions agree)."""
    index = {x: i for i, x in enumerate(train.links)}
    rows, rhs = _conditions(train.links, fixed, given)
    for g in train.gears:
        (a, b), (za, zb), c = g.links, g.teeth, g.carrier
        row = [Fraction(0)] * len(train.links)
        row[index[a]] += za
        row[index[b]] += -g.sign * zb
        row[index[c]] += -za + g.sign * zb
        rows.append(row)
        rhs.append(Fraction(0))
    return solve_exact(rows, rhs, len(train.links))


def _trains(train: GearTrain) -> list[tuple[str, dict[str, Fraction], bool]]:
    """The tabular method's first rows: for each carrier and each train of gears it
    holds (gears joined by pairs with that carrier), the turns of each gear when the
    first turns +1 with the carrier held (the products of the teeth), and whether the
    gears lock (a loop of gears whose products disagree)."""
    out = []
    for carrier in dict.fromkeys(g.carrier for g in train.gears):
        pairs = [g for g in train.gears if g.carrier == carrier]
        left = dict.fromkeys(x for g in pairs for x in g.links)
        while left:
            first = next(iter(left))
            ratios = {first: Fraction(1)}
            locked, grew = False, True
            while grew:
                grew = False
                for g in pairs:
                    (a, b), (za, zb) = g.links, g.teeth
                    for p, q, zp, zq in ((a, b, za, zb), (b, a, zb, za)):
                        if p in ratios:
                            r = ratios[p] * g.sign * Fraction(zp, zq)
                            if q not in ratios:
                                ratios[q], grew = r, True
                            elif ratios[q] != r:
                                locked = True
            for x in ratios:
                left.pop(x)
            out.append((carrier, ratios, locked))
    return out


def tabular_speeds(train: GearTrain, fixed: str, given: Mapping[str, Fraction]
                   ) -> tuple[list[Fraction | None], bool, list[tuple[str, dict, Fraction | None,
                                                                Fraction | None]]]:
    """Every link's speed by the tabular method (see the module's notes): unknowns
    ``x`` and ``y`` for each train of gears, each gear turning ``y + x r``, solved
    from the fixed link and the given speeds. Returns the speeds (None where left
    free), whether the conditions agree, and the table (carrier, ratios, x, y)."""
    trains = _trains(train)
    n = len(train.links)
    index = {x: i for i, x in enumerate(train.links)}
    size = n + len(trains)                   # the links' speeds, then each train's x
    rows, rhs = _conditions(train.links, fixed, given)
    rows = [r + [Fraction(0)] * len(trains) for r in rows]
    for k, (carrier, ratios, locked) in enumerate(trains):
        for link, r in ratios.items():       # w_link - w_carrier - x r = 0
            row = [Fraction(0)] * size
            row[index[link]] += 1
            row[index[carrier]] -= 1
            row[n + k] = -r
            rows.append(row)
            rhs.append(Fraction(0))
        if locked:                           # the gears cannot turn on their carrier
            row = [Fraction(0)] * size
            row[n + k] = Fraction(1)
            rows.append(row)
            rhs.append(Fraction(0))
    values, agree = solve_exact(rows, rhs, size)
    table = [(carrier, ratios, values[n + k], values[index[carrier]])
             for k, (carrier, ratios, _) in enumerate(trains)]
    return values[:n], agree, table


def train_kind(train: GearTrain, fixed: str) -> str:
    """The train's kind with ``fixed`` at rest, from its graph: ``"epicyclic"`` when a
    gear pair's carrier moves (is not the fixed link); else ``"compound"`` when a link
    carries two wheels (it meshes in two pairs with different numbers of teeth),
    ``"reverted"`` when such a train's two end gears turn about one axis (one R joint
    holds both), and ``"simple"`` otherwise (each shaft one wheel; an idler meshes
    with two gears by the same teeth)."""
    if any(g.carrier != fixed for g in train.gears):
        return "epicyclic"
    teeth: dict[str, set[int]] = {}
    meshes: dict[str, int] = {}
    for g in train.gears:
        for link, z in zip(g.links, g.teeth):
            teeth.setdefault(link, set()).add(z)
            meshes[link] = meshes.get(link, 0) + 1
    if all(len(z) == 1 for z in teeth.values()):
        return "simple"
    ends = [x for x, k in meshes.items() if k == 1]
    if any(train.coaxial(a, b) for i, a in enumerate(ends) for b in ends[i + 1:]):
        return "reverted"
    return "compound"


def _speed(value: float | int | Fraction) -> Fraction:
    """A speed as an exact rational (a float's decimal text, as it was typed)."""
    if isinstance(value, Fraction | int):
        return Fraction(value)
    return Fraction(repr(float(value)))


def _free(train: GearTrain, fixed: str) -> int:
    """How many speeds must be given with ``fixed`` at rest: the degrees of freedom."""
    count, given = 0, dict[str, Fraction]()
    while True:
        values, _ = willis_speeds(train, fixed, given)
        free = [x for x, v in zip(train.links, values) if v is None]
        if not free:
            return count
        given[free[0]] = Fraction(1)
        count += 1


def train_speeds(chain: Chain, *, fixed: str | None = None,
                 speeds: Mapping[str, float | int | Fraction] | None = None) -> TrainSpeeds:
    """Every link's speed (rpm, exact) in a gear train with ``fixed`` at rest and the
    links of ``speeds`` turning at theirs, by the Willis equations and by the tabular
    method (they must agree).

    ``fixed`` defaults to the file's fixed link; ``speeds`` to its driver at 1 rpm
    (so the speeds are ratios to it). Raises :class:`~chaingraph.errors.MechanismError`
    for a link that is not in the train, a speed for the fixed link, speeds that
    disagree with the gears, or too few speeds for the train's degrees of freedom."""
    train = gear_train(chain)
    m = chain.mechanism
    fixed = fixed if fixed is not None else (m.fixed if m is not None else None)
    if fixed is None:
        raise MechanismError("no fixed link: give 'fixed' (the file has no [mechanism])",
                             mechanism=chain.name, parameter="fixed")
    if fixed not in train.links:
        raise MechanismError(f"'fixed' names no link of the train: {fixed!r} (links: "
                             f"{', '.join(train.links)})", mechanism=chain.name,
                             parameter="fixed")
    if not speeds:
        driver = m.driver if m is not None else None
        if driver is None or driver == fixed:
            raise MechanismError("no input speed: give 'speeds' (a link's speed, rpm)",
                                 mechanism=chain.name, parameter="speeds")
        speeds = {driver: 1}
    given = {}
    for link, value in speeds.items():
        if link not in train.links:
            raise MechanismError(f"'speeds' names no link of the train: {link!r} (links: "
                                 f"{', '.join(train.links)})", mechanism=chain.name,
                                 parameter="speeds")
        if link == fixed:
            raise MechanismError(f"'speeds' gives a speed to the fixed link {link!r} "
                                 "(it is at rest)", mechanism=chain.name, parameter="speeds")
        given[link] = _speed(value)
    return _solved(chain, train, fixed, given)


def _solved(chain: Chain, train: GearTrain, fixed: str, given: dict[str, Fraction]
            ) -> TrainSpeeds:
    """The two computations run, checked against each other."""
    values, agree = willis_speeds(train, fixed, given)
    freedom = _free(train, fixed)
    if not agree:
        raise MechanismError(f"the speeds given disagree with the gears: the train has "
                             f"{freedom} degree(s) of freedom with {fixed!r} fixed, and "
                             f"{len(given)} speed(s) were given", mechanism=chain.name,
                             parameter="speeds")
    loose = [x for x, v in zip(train.links, values) if v is None]
    if loose:
        raise MechanismError(f"the train has {freedom} degree(s) of freedom with "
                             f"{fixed!r} fixed: give {freedom} speed(s) ({len(given)} "
                             f"given leave {', '.join(map(repr, loose))} free)",
                             mechanism=chain.name, parameter="speeds")
    tabular, agree2, table = tabular_speeds(train, fixed, given)
    if not agree2 or tabular != values:
        raise AssemblyError("the tabular method and the Willis equations disagree "
                            f"({tabular} against {values})", mechanism=chain.name)
    found = {x: v for x, v in zip(train.links, values) if v is not None}
    rows = tuple(TableRow(c, tuple(r.items()), x if x is not None else Fraction(0),
                          y if y is not None else Fraction(0)) for c, r, x, y in table)
    return TrainSpeeds(train, fixed, tuple(given.items()), found,
                       train_kind(train, fixed), freedom, rows)
