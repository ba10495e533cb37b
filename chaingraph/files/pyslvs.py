"""Pyslvs's mechanism expression, in and out.

Pyslvs (``pyslvs.expression_parser``, its Lark grammar) writes a mechanism as
``M[J[...], J[...], ...]``, one ``J`` per joint: its type (``R``; ``P``, a sliding pair
whose second and later links keep their direction; ``RP``, a pin in a slot), the slot's
angle ``A[degrees]`` for ``P`` and ``RP``, an optional ``color[...]``, its position
``P[x, y]`` and its links ``L[a, b, ...]``, the slot's link first. The link ``ground`` is
the frame; a joint on one link only is a point of that link. Link names are letters,
digits and ``_``; joints have no names (Pyslvs numbers them from 0). The expression
holds no input: Pyslvs keeps its inputs in its project, beside the expression.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import Any

from chaingraph.errors import InterchangeError
from chaingraph.files.imported import Imported, imported
from chaingraph.model.chain import Chain, Joint, chosen_inputs

__all__ = ["pyslvs_expression", "read_pyslvs", "link_names", "pins_in_slots", "FRAME"]

#: the name of the frame in a Pyslvs expression
FRAME = "ground"
COLORS = ("red", "green", "blue", "cyan", "magenta", "brick-red", "yellow", "gray",
          "orange", "pink", "black", "white", "dark-red", "dark-green", "dark-blue",
          "dark-cyan", "dark-magenta", "dark-yellow", "dark-gray", "dark-orange", "dark-pink")
TYPES = ("R", "P", "RP")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


# -- out: chaingraph -> Pyslvs ------------------------------------------------------------

def _refuse(chain: Chain, problem: str, where: str | None = None) -> InterchangeError:
    return InterchangeError(f"a Pyslvs expression cannot hold it: {problem}",
                            format="pyslvs", source=chain.source or chain.name, where=where)


def link_names(chain: Chain, fixed: str) -> dict[str, str]:
    """Each link's name as Pyslvs spells one (letters, digits, ``_``), the fixed link
    ``ground``, each unique.

    >>> from chaingraph.model.chain import Chain, Joint
    >>> link_names(Chain("x", (Joint("A", "R", ("frame", "connecting rod")),
    ...                        Joint("B", "R", ("connecting rod", "2nd")))), "frame")
    {'frame': 'ground', 'connecting rod': 'connecting_rod', '2nd': 'L_2nd'}
    """
    names = {fixed: FRAME}
    taken = {FRAME}
    for link in chain.links:
        if link == fixed:
            continue
        name = re.sub(r"[^A-Za-z0-9_]", "_", link) or "L"
        name = name if _NAME.match(name) else f"L_{name}"
        out, k = name, 1
        while out in taken:
            k += 1
            out = f"{name}_{k}"
        taken.add(out)
        names[link] = out
    return names


def pins_in_slots(chain: Chain, keep: set[str | None]) -> dict[str, str]:
    """``{P joint: R joint}`` of the blocks that are a pin in a slot, Pyslvs's ``RP``
    joint: a block (neither the fixed link nor the driver) whose only other joint is an
    R pin, no point on it; the slot is the P joint's guide."""
    out = {}
    for p in (j for j in chain.joints if j.kind == "P"):
        block = p.links[1]
        others = [j for j in chain.joints_of(block) if j.id != p.id]
        if block not in keep and len(others) == 1 and others[0].kind == "R" \
                and others[0].at is not None and p.links[0] not in others[0].links \
                and not any(q.link == block for q in chain.points):
            out[p.id] = others[0].id
    return out


def _joint_text(chain: Chain, j: Joint, names: dict[str, str], pins: dict[str, str],
                fixed: str) -> str:
    """One joint's ``J[...]``: R, P, or RP for a P joint whose block is a pin."""
    links = [*(x for x in j.links if x == fixed), *(x for x in j.links if x != fixed)]
    assert j.at is not None
    at = j.at
    if j.kind == "P" and j.id in pins:
        pin = chain.joint(pins[j.id])
        assert j.axis is not None and pin.at is not None
        kind, at = f"RP, A[{_number(j.axis)}]", pin.at
        links = [j.links[0], *(x for x in pin.links if x != j.links[1])]
    elif j.kind == "P":
        assert j.axis is not None
        kind, links = f"P, A[{_number(j.axis)}]", list(j.links)
    else:
        kind = "R"
    return (f"J[{kind}, color[Green], P[{_number(at[0])}, {_number(at[1])}], "
            f"L[{', '.join(names[x] for x in links)}]]")


def _number(x: float) -> str:
    """A number as the grammar reads it, to the last digit (``repr``)."""
    text = repr(float(x))
    return text if "." in text or "e" in text else text + ".0"


def pyslvs_expression(chain: Chain) -> str:
    """The mechanism as a Pyslvs expression (``parse_vpoints`` reads it; Pyslvs loads it
    in its mechanism's box as it is).

    R joints are ``R`` joints on their links, each P joint a ``P`` joint on the link
    that carries the guide, then the block, at the pair's point with its axis as the
    slot's angle, and a block that is only a pin in a slot (its one other joint an R
    pin) Pyslvs's ``RP`` joint at the pin, on the slot's link and the pin's others; each
    point a joint on its one link. The fixed link is called
    ``ground``; other names become names Pyslvs accepts (``connecting rod``:
    ``connecting_rod``). Positions are written to the last digit. The input's pivot is
    written first (Pyslvs keeps inputs outside the expression; :func:`read_pyslvs`
    takes the link on the first ground pivot as the driver).

    Parameters
    ----------
    chain : Chain
        A mechanism (the fixed link is the ground) drawn in a pose, its joints R and P.

    Returns
    -------
    str
        The expression, one joint a line.

    Raises
    ------
    InterchangeError
        When the expression cannot hold the mechanism, with the reason: no fixed link, a
        higher pair, a joint without a drawn position.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> print(pyslvs_expression(chaingraph.load(catalog_path("reciprocating-engine"))))
    M[
      J[R, color[Green], P[0.0, 0.0], L[ground, crank]],
      J[R, color[Green], P[20.000000000000004, 34.64101615137754], L[crank, connecting_rod]],
      J[RP, A[0.0], color[Green], P[176.20499351813308, 0.0], L[ground, connecting_rod]],
    ]
    """
    if chain.space != "planar" or chain.cams or any(j.kind not in ("R", "P")
                                                    for j in chain.joints):
        kinds = sorted({j.kind for j in chain.joints} - {"R", "P"}) or ["a cam"]
        raise _refuse(chain, f"Pyslvs's joints are turning and sliding pairs (this has "
                             f"{', '.join(kinds)})")
    if chain.mechanism is None:
        raise _refuse(chain, "it has no [mechanism]: the ground of a Pyslvs mechanism is "
                             "its fixed link")
    fixed, driver, inputs = chosen_inputs(chain)
    assert fixed is not None
    names = link_names(chain, fixed)
    first = inputs[0].joint if inputs else next(
        (j.id for j in chain.joints if j.kind == "R" and {fixed, driver} <= set(j.links)),
        None)
    pins = pins_in_slots(chain, {fixed, driver})
    lines = []
    for j in sorted(chain.joints, key=lambda j: j.id != first):
        if j.at is None:
            raise _refuse(chain, "no drawn position", f"joint {j.id!r}")
        if j.id not in pins.values():
            lines.append(_joint_text(chain, j, names, pins, fixed))
    for q in chain.points:
        if q.at is None:
            raise _refuse(chain, "no drawn position", f"point {q.id!r}")
        lines.append(f"J[R, color[Green], P[{_number(q.at[0])}, {_number(q.at[1])}], "
                     f"L[{names[q.link]}]]")
    return "M[\n" + "".join(f"  {line},\n" for line in lines) + "]"


# -- in: Pyslvs -> chaingraph -------------------------------------------------------------

_TOKEN = re.compile(r"""
    (?P<space>\s+|\#\[[\s\S]*?\#\][^\n]*|\#[^\n]*)
  | (?P<number>[+-]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)
  | (?P<word>[A-Za-z_][A-Za-z0-9_-]*)
  | (?P<open>\[) | (?P<close>\]) | (?P<comma>,) | (?P<paren>[()])
  | (?P<other>.)""", re.VERBOSE)


class _Parser:
    """Pyslvs's grammar (``pyslvs.expression_parser._GRAMMAR``), read by hand."""

    def __init__(self, text: str, source: str) -> None:
        self.source = source
        self.tokens: list[tuple[str, str, int]] = []
        line = 1
        for m in _TOKEN.finditer(text):
            kind = m.lastgroup or "other"
            if kind == "other":
                raise self.bad(f"unexpected {m.group()!r}", line)
            if kind != "space":
                self.tokens.append((kind, m.group(), line))
            line += m.group().count("\n")
        self.k = 0

    def bad(self, problem: str, line: int | None = None) -> InterchangeError:
        if line is None:
            line = self.tokens[min(self.k, len(self.tokens) - 1)][2] if self.tokens else 1
        return InterchangeError(f"not a Pyslvs expression: {problem}", format="pyslvs",
                                source=self.source, where=f"line {line}", line=line)

    def peek(self) -> tuple[str, str]:
        return self.tokens[self.k][:2] if self.k < len(self.tokens) else ("end", "")

    def take(self, kind: str, text: str | None = None) -> str:
        got = self.peek()
        if got[0] != kind or (text is not None and got[1] != text):
            want = text or kind
            raise self.bad(f"expected {want!r}, found {got[1] or 'the end'!r}")
        self.k += 1
        return got[1]

    def head(self, word: str) -> None:
        self.take("word", word)
        self.take("open")

    def mechanism(self) -> list[dict[str, Any]]:
        self.head("M")
        joints = []
        while self.peek()[0] != "close":
            joints.append(self.joint())
            if self.peek()[0] != "comma":
                break
            self.take("comma")
        self.take("close")
        if self.peek()[0] != "end":
            raise self.bad(f"{self.peek()[1]!r} after the mechanism's closing ']'")
        return joints

    def number(self) -> float:
        return float(self.take("number"))

    def joint(self) -> dict[str, Any]:
        line = self.tokens[self.k][2] if self.k < len(self.tokens) else 0
        self.head("J")
        kind = self.take("word")
        if kind not in TYPES:
            raise self.bad(f"unknown joint type {kind!r} (expected one of "
                           f"{', '.join(TYPES)})")
        self.take("comma")
        joint: dict[str, Any] = {"type": kind, "line": line}
        if self.peek() == ("word", "A"):
            self.head("A")
            joint["angle"] = self.number()
            self.take("close")
            self.take("comma")
        if (kind == "R") == ("angle" in joint):
            raise self.bad(f"a{'n R' if kind == 'R' else f' {kind}'} joint "
                           f"{'takes no' if kind == 'R' else 'needs its'} angle A[...]")
        if self.peek() == ("word", "color"):
            self.color()
            self.take("comma")
        self.head("P")
        x = self.number()
        self.take("comma")
        y = self.number()
        self.take("close")
        self.take("comma")
        self.head("L")
        links: list[str] = []
        while self.peek()[0] == "word":
            links.append(self.take("word"))
            if self.peek()[0] != "comma":
                break
            self.take("comma")
        self.take("close")
        self.take("close")
        bad = [x for x in links if not _NAME.match(x)]
        if bad:
            raise self.bad(f"{bad[0]!r} is not a link name (letters, digits and _)")
        return {**joint, "at": [x, y], "links": links}

    def color(self) -> None:
        self.head("color")
        if self.peek()[0] == "paren":
            self.take("paren", "(")
            for k in range(3):
                self.take("number")
                if k < 2:
                    self.take("comma")
            self.take("paren", ")")
        elif self.peek()[1].lower() not in COLORS:
            raise self.bad(f"unknown color {self.peek()[1]!r}")
        else:
            self.k += 1
        self.take("close")


def _structure(parsed: list[dict[str, Any]], notes: list[str]
               ) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """The chain file's joints and points: joint ``k`` is ``Pk``; an ``RP`` joint a pin
    ``Pk`` on a block ``Pk_block`` sliding in the slot ``Pk_slot``."""
    taken = {x for j in parsed for x in j["links"]}
    joints: list[dict[str, Any]] = []
    points: list[dict[str, Any]] = []
    for k, j in enumerate(parsed):
        name, links = f"P{k}", list(dict.fromkeys(j["links"]))
        if len(links) == 0:
            notes.append(f"{name} (line {j['line']}) is on no link: left out")
        elif len(links) == 1:
            points.append({"id": name, "link": links[0], "at": j["at"]})
            if j["type"] != "R":
                notes.append(f"{name}: a {j['type']} joint on one link only: a point of "
                             f"{links[0]!r} here")
        elif j["type"] == "R":
            joints.append({"id": name, "kind": "R", "links": links, "at": j["at"]})
        elif j["type"] == "P" and len(links) == 2:
            joints.append({"id": name, "kind": "P", "links": links, "at": j["at"],
                           "axis": j["angle"]})
        elif j["type"] == "P":
            raise InterchangeError(f"a P joint on {len(links)} links: chaingraph's sliding "
                                   f"pair joins two (write the others with an R joint)",
                                   format="pyslvs", where=name)
        else:
            block = f"{name}_block"
            while block in taken:
                block += "_"
            taken.add(block)
            joints.append({"id": f"{name}_slot", "kind": "P", "links": [links[0], block],
                           "at": j["at"], "axis": j["angle"]})
            joints.append({"id": name, "kind": "R", "links": [block, *links[1:]],
                           "at": j["at"]})
    return joints, points


def _given_inputs(joints: list[dict[str, Any]], inputs: Sequence[tuple[int, int]],
                  notes: list[str]) -> dict[str, Any]:
    """The [mechanism] of Pyslvs's input pairs ``(base, drive)``: the link joining
    joints ``Pbase`` and ``Pdrive`` turns about ``Pbase`` on the ground."""
    by_id = {j["id"]: j for j in joints}
    chosen: list[tuple[str, str]] = []
    for base, drive in inputs:
        slot = by_id.get(f"P{base}_slot") or by_id.get(f"P{base}")
        if base == drive and slot is not None and slot["kind"] == "P":
            chosen.append((slot["id"], ""))         # the slider driven along its slot
            continue
        b, d = by_id.get(f"P{base}"), by_id.get(f"P{drive}")
        common = sorted(set(b["links"]) & set(d["links"]) - {FRAME}) if b and d else []
        if b is None or d is None or not common:
            raise InterchangeError(f"input ({base}, {drive}): joints P{base} and P{drive} "
                                   f"are not two joints of one link", format="pyslvs",
                                   where="inputs")
        if FRAME not in b["links"] or b["kind"] != "R":
            raise InterchangeError(f"input ({base}, {drive}): P{base} is not a pivot on "
                                   f"the ground; chaingraph's inputs here turn about one",
                                   format="pyslvs", where="inputs")
        chosen.append((b["id"], common[0]))
    pivots = [b for b, _ in chosen]
    if len(chosen) == 1 and chosen[0][1] and len(by_id[pivots[0]]["links"]) == 2:
        return {"fixed": FRAME, "driver": chosen[0][1]}
    if len(set(pivots)) < len(pivots) or any(len(by_id[b]["links"]) != 2 for b in pivots):
        notes.append(f"inputs {list(inputs)}: a pivot of several links drives one of them "
                     f"(chaingraph's input is a joint); no input set")
        return {"fixed": FRAME}
    return {"fixed": FRAME, "inputs": pivots}


def _mechanism(joints: list[dict[str, Any]], driver: str | None,
               inputs: Sequence[tuple[int, int]] | None, notes: list[str]
               ) -> dict[str, Any] | None:
    """The [mechanism]: the ground fixed, the inputs or the driver given, or the link on
    the first ground pivot."""
    links = {x for j in joints for x in j["links"]}
    if FRAME not in links:
        notes.append(f"no link is called {FRAME!r}: imported as a chain, nothing fixed")
        return None
    if inputs:
        return _given_inputs(joints, inputs, notes)
    if driver is not None:
        if driver not in links:
            raise InterchangeError(f"no link {driver!r} to drive (links: "
                                   f"{', '.join(sorted(links))})", format="pyslvs",
                                   where="driver")
        return {"fixed": FRAME, "driver": driver}
    pivot = next((j for j in joints if j["kind"] == "R" and FRAME in j["links"]
                  and len(j["links"]) == 2), None)
    if pivot is None:
        notes.append("the expression holds no input and no ground pivot has one link to "
                     "turn: no driver")
        return {"fixed": FRAME}
    link = next(x for x in pivot["links"] if x != FRAME)
    notes.append(f"the expression holds no input: {link!r}, on the first ground pivot "
                 f"{pivot['id']}, taken as the driver")
    return {"fixed": FRAME, "driver": link}


def read_pyslvs(text: str, *, source: str = "<string>", driver: str | None = None,
                inputs: Sequence[tuple[int, int]] | None = None,
                name: str | None = None) -> Imported:
    """A Pyslvs mechanism expression as a chain file.

    Joint ``k`` of the expression is joint ``Pk`` (an ``R`` joint on one link a point
    of it; an ``RP`` joint a pin ``Pk`` on a block ``Pk_block`` that slides in the slot
    ``Pk_slot``); ``ground`` is the fixed link; colours are left.

    Parameters
    ----------
    text : str
        The expression (``M[J[...], ...]``; comments ``#`` as Pyslvs allows them).
    source : str, optional
        Where it came from, for the messages.
    driver : str, optional
        The input link. By default the link on the first ground pivot (an R joint of
        the ground and one other link), said in the notes: the expression holds none.
    inputs : sequence of (int, int), optional
        Pyslvs's input pairs ``(base, drive)`` (its project and ``example_list`` keep
        them): the link of joints ``base`` and ``drive`` turns about ``base``, a pivot
        on the ground. Takes precedence over ``driver``.
    name : str, optional
        The chain's name (default: "Pyslvs mechanism").

    Returns
    -------
    Imported
        The chain file and the notes: what could not be carried over.

    Raises
    ------
    InterchangeError
        Text that is not an expression (with its line), an unknown joint type, a
        ``P`` joint on more than two links; one line.

    Examples
    --------
    >>> model = read_pyslvs("M[J[R, P[0, 0], L[ground, crank]], "
    ...                     "J[R, P[10, 20], L[crank, rod]], "
    ...                     "J[RP, A[0], P[60, 0], L[ground, rod]]]")
    >>> [(j.id, j.kind, j.links) for j in model.chain.joints]
    [('P0', 'R', ('ground', 'crank')), ('P1', 'R', ('crank', 'rod')), ('P2_slot', 'P', ('ground', 'P2_block')), ('P2', 'R', ('P2_block', 'rod'))]
    >>> model.notes
    ("the expression holds no input: 'crank', on the first ground pivot P0, taken as the driver",)
    """
    parsed = _Parser(text, source).mechanism()
    notes: list[str] = []
    try:
        joints, points = _structure(parsed, notes)
        mechanism = _mechanism(joints, driver, inputs, notes)
    except InterchangeError as e:
        raise InterchangeError(e.problem, format="pyslvs", source=source,
                               where=e.where) from None
    keys: dict[str, Any] = {"name": name or "Pyslvs mechanism",
                            "notes": "Imported from a Pyslvs mechanism expression.",
                            "joints": joints}
    if points:
        keys["points"] = points
    if mechanism is not None:
        if points and ("driver" in mechanism or "inputs" in mechanism):
            mechanism["output"] = points[0]["id"]
        keys["mechanism"] = mechanism
    return imported(keys, notes, source=source)
