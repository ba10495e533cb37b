"""pylinkage 1.3's JSON serialisation of a mechanism, in and out.

pylinkage (``pylinkage.mechanism.serialization``: ``mechanism_to_dict``,
``mechanism_from_dict``) writes a mechanism as ``{"name", "joints", "links", "ground"}``:
joints of type ``ground`` (a pivot on the frame), ``revolute``, ``prismatic`` (a pin that
slides along a line fixed on the frame: ``line_point`` and ``axis``) and ``tracker`` (a
point at ``distance`` and ``angle`` from two reference joints); links of type ``ground``,
``driver`` (a crank turning ``angular_velocity`` radians a step about its
``motor_joint`` from ``initial_angle``), ``arc_driver`` (one rocking between ``arc_start``
and ``arc_end``) and ``link``, each a rigid body on the joints it lists.

Here a pylinkage ``prismatic`` joint is a slider of its own: an R joint (the pin) on a
block that slides in a P joint on the frame.
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from typing import Any

from chaingraph._util.disjoint import DisjointSets
from chaingraph.errors import ChainGraphError, InterchangeError
from chaingraph.files.imported import Imported, imported
from chaingraph.kinematics import build_plan, feasible_range
from chaingraph.model.chain import Chain, Joint, chosen_inputs, line_direction

__all__ = ["pylinkage_json", "pylinkage_dict", "read_pylinkage", "STEPS_PER_TURN",
           "LIMIT_MARGIN"]

#: a crank written for pylinkage turns a degree a step (chaingraph's sweep of a turn)
STEPS_PER_TURN = 360
#: how far (radians) inside its limits a driver that rocks is written to rock
LIMIT_MARGIN = 1e-9
JOINT_TYPES = ("ground", "revolute", "prismatic", "tracker")
LINK_TYPES = ("ground", "driver", "arc_driver", "link")
LEGACY_TYPES = ("Static", "Crank", "Revolute", "Fixed", "Prismatic", "Linear")


def _refuse(chain: Chain, problem: str, where: str | None = None) -> InterchangeError:
    return InterchangeError(f"pylinkage cannot hold it: {problem}", format="pylinkage",
                            source=chain.source or chain.name, where=where)


# -- out: chaingraph -> pylinkage ---------------------------------------------------------

def _crank(chain: Chain) -> tuple[str, Joint, str, tuple[float, float] | None]:
    """``(fixed, motor joint, driver link, sweep)`` of the mechanism's one crank; the
    sweep ``(from, to)`` in degrees when its input gives one."""
    if chain.mechanism is None:
        raise _refuse(chain, "it has no [mechanism]: a pylinkage mechanism needs its "
                             "ground and a driver")
    fixed, driver, inputs = chosen_inputs(chain)
    assert fixed is not None
    if inputs:
        if len(inputs) != 1:
            raise _refuse(chain, f"{len(inputs)} inputs: pylinkage drives one crank here")
        motor = chain.joint(inputs[0].joint)
        movers = [x for x in motor.links if x != fixed]
        if motor.kind != "R" or fixed not in motor.links or len(movers) != 1:
            raise _refuse(chain, "its input is not a crank (an R joint between the fixed "
                                 "link and one other): pylinkage drives cranks only",
                          f"joint {motor.id!r}")
        start, stop = inputs[0].start, inputs[0].stop
        sweep = None if start is None or stop is None else (start, stop)
        return fixed, motor, movers[0], sweep
    if driver is None:
        raise _refuse(chain, "it has no driver: pylinkage drives a crank")
    motors = [j for j in chain.joints if j.kind == "R" and {fixed, driver} <= set(j.links)]
    if len(motors) != 1 or len(motors[0].links) != 2:
        raise _refuse(chain, f"the driver {driver!r} does not turn about one R joint of "
                             f"its own on the fixed link")
    return fixed, motors[0], driver, None


def _sliders(chain: Chain, fixed: str) -> dict[str, tuple[Joint, Joint]]:
    """``{block: (P joint, pin)}``: each sliding pair is a block sliding on the frame
    that carries one pin (an R joint to moving links), as pylinkage's prismatic joint."""
    out: dict[str, tuple[Joint, Joint]] = {}
    for p in (j for j in chain.joints if j.kind == "P"):
        where = f"joint {p.id!r}"
        if fixed not in p.links:
            raise _refuse(chain, f"a sliding pair between two moving links {p.links}: "
                                 f"pylinkage slides a pin along a line of the frame only",
                          where)
        block = next(x for x in p.links if x != fixed)
        others = [j for j in chain.joints_of(block) if j.id != p.id]
        if len(others) != 1 or others[0].kind != "R" or fixed in others[0].links:
            carried = ", ".join(f"{j.kind} joint {j.id!r}" for j in others) or "nothing"
            raise _refuse(chain, f"the block {block!r} carries {carried}: pylinkage's "
                                 f"slider is one pin to moving links", where)
        if any(q.link == block for q in chain.points):
            raise _refuse(chain, f"a point on the block {block!r}: pylinkage's slider has "
                                 f"no body to carry it", where)
        out[block] = (p, others[0])
    return out


def _tracker(chain: Chain, point_id: str, at: tuple[float, float],
             refs: Sequence[Joint]) -> dict[str, Any]:
    """A tracer point as a pylinkage tracker: from two joints of its link."""
    ordered = sorted(refs, key=lambda j: j.id)
    first = ordered[0] if ordered else None
    second = next((j for j in ordered[1:] if first is not None and first.at is not None
                   and j.at is not None and math.dist(j.at, first.at) > 0), None)
    if first is None or second is None or first.at is None or second.at is None:
        raise _refuse(chain, "its link has no two joints apart to measure it from "
                             "(a tracker needs two)", f"point {point_id!r}")
    base = math.atan2(second.at[1] - first.at[1], second.at[0] - first.at[0])
    turn = math.atan2(at[1] - first.at[1], at[0] - first.at[0])
    return {"id": point_id, "type": "tracker", "position": list(at),
            "ref_joint1_id": first.id, "ref_joint2_id": second.id,
            "distance": math.dist(at, first.at),
            "angle": math.remainder(turn - base, math.tau)}


def _joint_entries(chain: Chain, fixed: str, pins: dict[str, Joint]) -> list[dict[str, Any]]:
    """The joints (pivots, pins, sliding pins), not yet the trackers."""
    entries = []
    for j in chain.joints:
        if j.kind == "P":
            continue
        if j.at is None:
            raise _refuse(chain, "no drawn position", f"joint {j.id!r}")
        entry: dict[str, Any] = {"id": j.id, "position": list(j.at)}
        if fixed in j.links:
            entry["type"] = "ground"
        elif j.id in pins:
            p = pins[j.id]
            assert p.axis is not None
            axis = math.radians(p.axis)
            entry.update(type="prismatic", axis=[math.cos(axis), math.sin(axis)],
                         line_point=list(j.at), slide_distance=0.0)
        else:
            entry["type"] = "revolute"
        entries.append(entry)
    return entries


def _rocking(chain: Chain) -> tuple[float, float] | None:
    """A driver that cannot turn fully: the range it rocks over (degrees), pulled in
    from each limit by ``LIMIT_MARGIN`` (at a limit the loop closes only to rounding,
    and pylinkage's circle intersection finds no point); None for a crank."""
    try:
        found = feasible_range(build_plan(chain))
    except ChainGraphError:
        return None
    if found is None:
        return None
    margin = math.degrees(LIMIT_MARGIN)
    return found[0] + margin, found[1] - margin


def _unique(name: str, taken: set[str]) -> str:
    out, k = name, 1
    while out in taken:
        k += 1
        out = f"{name} {k}"
    taken.add(out)
    return out


def _driver_entries(chain: Chain, motor: Joint, driver: str,
                    sweep: tuple[float, float] | None, taken: set[str]
                    ) -> list[dict[str, Any]]:
    """The crank (a binary driver link), and a rigid link over all its joints when it
    carries more than its two."""
    joints = [j for j in chain.joints_of(driver) if j.kind == "R"]
    assert motor.at is not None
    rest = [j for j in joints if j.id != motor.id]
    output = next((j for j in rest if j.at is not None and math.dist(j.at, motor.at) > 0),
                  None)
    if output is None or output.at is None:
        raise _refuse(chain, "the driver has no joint apart from its pivot to turn",
                      f"link {driver!r}")
    angle = math.atan2(output.at[1] - motor.at[1], output.at[0] - motor.at[0])
    crank: dict[str, Any] = {"id": driver, "type": "driver",
                             "joints": [motor.id, output.id],
                             "angular_velocity": math.tau / STEPS_PER_TURN,
                             "initial_angle": angle, "motor_joint": motor.id}
    if sweep is None:
        sweep = _rocking(chain)
    if sweep is not None:
        low, high = sorted(math.radians(v) for v in sweep)
        crank.update(type="arc_driver", arc_start=low, arc_end=high)
    entries = [crank]
    if len(joints) > 2:           # welded to the crank: the same body
        entries.append({"id": _unique(f"{driver} plate", taken), "type": "link",
                        "joints": [j.id for j in joints]})
    return entries


def pylinkage_dict(chain: Chain) -> dict[str, Any]:
    """The mechanism as pylinkage's ``mechanism_to_dict`` writes one; see
    :func:`pylinkage_json`."""
    if chain.space != "planar" or chain.cams or any(j.kind not in ("R", "P")
                                                    for j in chain.joints):
        kinds = sorted({j.kind for j in chain.joints} - {"R", "P"}) or ["a cam"]
        raise _refuse(chain, f"pylinkage's joints are turning and sliding pairs "
                             f"(this has {', '.join(kinds)})")
    fixed, motor, driver, sweep = _crank(chain)
    sliders = _sliders(chain, fixed)
    pins = {pin.id: p for p, pin in sliders.values()}
    joints = _joint_entries(chain, fixed, pins)
    taken = set(chain.links)
    links: list[dict[str, Any]] = [{"id": fixed, "type": "ground", "joints": [
        j.id for j in chain.joints_of(fixed) if j.kind == "R"]}]
    links += _driver_entries(chain, motor, driver, sweep, taken)
    for link in chain.links:
        if link not in (fixed, driver) and link not in sliders:
            links.append({"id": link, "type": "link",
                          "joints": [j.id for j in chain.joints_of(link) if j.kind == "R"]})
    for q in chain.points:
        if q.link in sliders:
            raise _refuse(chain, "on a slider block, which pylinkage does not model",
                          f"point {q.id!r}")
        if q.at is None:
            raise _refuse(chain, "no drawn position", f"point {q.id!r}")
        refs = [j for j in chain.joints_of(q.link) if j.kind == "R"]
        joints.append(_tracker(chain, q.id, q.at, refs))
    return {"name": chain.name, "joints": joints, "links": links, "ground": fixed}


def pylinkage_json(chain: Chain) -> str:
    """The mechanism as pylinkage 1.3's JSON serialisation (``mechanism_from_json``
    loads it, and its ``step`` traces the same paths).

    The crank turns a degree a step from its drawn direction (``angular_velocity``
    2 pi / 360); a driver that cannot turn fully becomes an ``arc_driver`` over the
    range it rocks, 1e-9 rad inside each limit (``LIMIT_MARGIN``), and an input swept
    between two values an ``arc_driver`` between them; each sliding pair's block becomes a prismatic joint at its pin, sliding on
    the line through the pin along the pair's axis; each point a tracker from two
    joints of its link.

    Parameters
    ----------
    chain : Chain
        A mechanism drawn in a pose (a file given by lengths, once loaded, is drawn),
        its joints R and P, its input a crank on the fixed link.

    Returns
    -------
    str
        The JSON text (indented as ``mechanism_to_json`` writes it).

    Raises
    ------
    InterchangeError
        When pylinkage cannot hold the mechanism, with the reason: no mechanism or no
        crank, a sliding pair between two moving links or a block that carries more
        than one pin, a higher pair, several inputs.

    Examples
    --------
    >>> import json, chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> data = json.loads(pylinkage_json(chaingraph.load(catalog_path("beam-engine"))))
    >>> [(j["id"], j["type"]) for j in data["joints"]]
    [('A', 'ground'), ('B', 'revolute'), ('C', 'revolute'), ('D', 'ground'), ('E', 'tracker')]
    """
    return json.dumps(pylinkage_dict(chain), indent=2) + "\n"


# -- in: pylinkage -> chaingraph ----------------------------------------------------------

class _Reader:
    """A pylinkage mechanism's dict, checked, as the parts of a chain file."""

    def __init__(self, data: Any, source: str) -> None:
        self.source = source
        if not isinstance(data, dict) or not isinstance(data.get("joints"), list) \
                or not isinstance(data.get("links"), list):
            raise self.bad("not a pylinkage mechanism: expected an object with 'joints' "
                           "and 'links' lists")
        legacy = [j.get("type") for j in data["joints"] if isinstance(j, dict)
                  and j.get("type") in LEGACY_TYPES]
        if legacy:
            raise self.bad(f"pylinkage's legacy format (joint type {legacy[0]!r}): load it "
                           f"in pylinkage 1.3 and save it with mechanism_to_json")
        self.joints = {j["id"]: j for j in (self.joint(k, j) for k, j in
                                            enumerate(data["joints"]))}
        self.links = [self.link(k, x) for k, x in enumerate(data["links"])]
        self.data = data

    def bad(self, problem: str, where: str | None = None) -> InterchangeError:
        return InterchangeError(problem, format="pylinkage", source=self.source, where=where)

    def typed(self, what: str, k: int, entry: Any, types: Sequence[str],
              default: str) -> tuple[str, str]:
        """A joint's or link's entry checked for its id and type: (where, type)."""
        if not isinstance(entry, dict) or not isinstance(entry.get("id"), str) \
                or not entry["id"]:
            raise self.bad(f"a {what} needs an object with a string 'id'", f"{what} #{k + 1}")
        where = f"{what} {entry['id']!r}"
        kind = entry.get("type", default)
        if kind not in types:
            raise self.bad(f"unknown type {kind!r} (expected one of {', '.join(types)})",
                           where)
        return where, kind

    def joint(self, k: int, j: Any) -> dict[str, Any]:
        where, kind = self.typed("joint", k, j, JOINT_TYPES, "revolute")
        if kind != "tracker" and not _pair(j.get("position")):
            raise self.bad("its position is not two finite numbers", where)
        if kind == "prismatic" and not (_pair(j.get("axis", [1.0, 0.0]))
                                        and _pair(j.get("line_point", [0.0, 0.0]))
                                        and math.hypot(*j.get("axis", [1.0, 0.0])) > 0):
            raise self.bad("its axis and line_point must be two finite numbers each, "
                           "the axis not zero", where)
        return {**j, "type": kind}

    def link(self, k: int, x: Any) -> dict[str, Any]:
        where, kind = self.typed("link", k, x, LINK_TYPES, "link")
        ids = x.get("joints", [])
        if not isinstance(ids, list) or any(i not in self.joints for i in ids):
            missing = [i for i in ids if i not in self.joints] if isinstance(ids, list) else []
            raise self.bad(f"names no joint {missing[0]!r}" if missing else
                           "its 'joints' must be a list of joint ids", where)
        return {**x, "type": kind, "joints": list(dict.fromkeys(ids))}


def _pair(value: object) -> bool:
    return (isinstance(value, (list, tuple)) and len(value) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                    and math.isfinite(v) for v in value))


def _bodies(r: _Reader, notes: list[str]) -> tuple[dict[str, str], str]:
    """``({pylinkage link: chaingraph link}, frame)``: links that share two joints or
    more are one rigid body (a crank and the plate welded to it, a link on two ground
    joints and the frame)."""
    grounds = [x for x in r.links if x["type"] == "ground"]
    named = [x for x in grounds if x["id"] == r.data.get("ground")]
    if not grounds:
        raise r.bad("no ground link: a pylinkage mechanism needs its frame")
    frame = (named or grounds)[0]["id"]
    pivots = {i for x in grounds for i in x["joints"]} | {
        i for i, j in r.joints.items() if j["type"] == "ground"} | {
        x.get("motor_joint") for x in r.links if x["type"] in ("driver", "arc_driver")}
    sets = DisjointSets([x["id"] for x in r.links])
    for x in grounds:
        sets.join(frame, x["id"])
    solid = [(x["id"], {i for i in x["joints"] if r.joints[i]["type"] != "tracker"})
             for x in r.links]
    for k, (a, ja) in enumerate(solid):
        for b, jb in solid[k + 1:]:
            if len(ja & jb) >= 2 and sets.join(a, b):
                shared = ", ".join(sorted(ja & jb))
                notes.append(f"links {a!r} and {b!r} share joints {shared}: one rigid "
                             f"link here")
        if a != frame and len(ja & pivots) >= 2 and sets.join(frame, a):
            notes.append(f"link {a!r} is on two ground joints: part of the frame here")
    rank = {"ground": 0, "driver": 1, "arc_driver": 1, "link": 2}
    names: dict[str, str] = {}
    for block in sets.blocks().values():
        block = sorted(block, key=lambda i: (i != frame, rank[next(
            x["type"] for x in r.links if x["id"] == i)]))
        names.update((i, block[0]) for i in block)
    return names, frame


def _projected(j: dict[str, Any]) -> tuple[tuple[float, float], float]:
    """A prismatic joint's position on its line, and how far it was off it."""
    (x, y), (px, py), (ax, ay) = j["position"], j.get("line_point", [0.0, 0.0]), \
        j.get("axis", [1.0, 0.0])
    n = math.hypot(ax, ay)
    ux, uy = ax / n, ay / n
    t = (x - px) * ux + (y - py) * uy
    on = (px + t * ux, py + t * uy)
    return on, math.dist(on, (x, y))


def _structure(r: _Reader, names: dict[str, str], frame: str, notes: list[str]
               ) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    """The chain file's joints and points from pylinkage's joints (trackers aside)."""
    links_of: dict[str, list[str]] = {i: [] for i in r.joints}
    for x in r.links:
        for i in x["joints"]:
            if names[x["id"]] not in links_of[i]:
                links_of[i].append(names[x["id"]])
    taken = set(names.values())
    ids = set(r.joints)
    joints: list[dict[str, Any]] = []
    points: list[dict[str, Any]] = []
    for i, j in r.joints.items():
        if j["type"] == "tracker":
            continue
        links = links_of[i]
        if j["type"] == "ground" and frame not in links:
            links = [frame, *links]
        at = [float(v) for v in j["position"]]
        if j["type"] == "prismatic":
            if frame in links:
                raise r.bad("a prismatic joint on the ground link", f"joint {i!r}")
            on, off = _projected(j)
            if off > 1e-9 * max(1.0, math.hypot(*at)):
                notes.append(f"joint {i!r}: drawn {off:.6g} off its slide line; put on "
                             f"the line")
            block = _unique(f"slider {i}", taken)
            ax, ay = j.get("axis", [1.0, 0.0])
            axis = math.degrees(math.atan2(ay, ax))
            joints.append({"id": i, "kind": "R", "links": [*links, block], "at": list(on)})
            joints.append({"id": _unique(f"{i} guide", ids), "kind": "P",
                           "links": [frame, block], "at": list(on), "axis": axis})
        elif len(links) >= 2:
            joints.append({"id": i, "kind": "R", "links": links, "at": at})
        elif links:
            points.append({"id": i, "link": links[0], "at": at})
        else:
            notes.append(f"joint {i!r} is on no link: left out")
    return joints, points


def _trackers(r: _Reader, names: dict[str, str], joints: list[dict[str, Any]],
              notes: list[str]) -> list[dict[str, Any]]:
    """Trackers as points of the link that holds both their reference joints."""
    at = {j["id"]: j["at"] for j in joints}
    links_of = {j["id"]: set(j["links"]) for j in joints}
    out = []
    for i, j in r.joints.items():
        if j["type"] != "tracker":
            continue
        a, b = j.get("ref_joint1_id"), j.get("ref_joint2_id")
        common = sorted(links_of.get(a, set()) & links_of.get(b, set()))
        if not common or a not in at or b not in at or a == b:
            notes.append(f"tracker {i!r}: its reference joints {a!r} and {b!r} share no "
                         f"link; left out")
            continue
        (x1, y1), (x2, y2) = at[a], at[b]
        turn = math.atan2(y2 - y1, x2 - x1) + float(j.get("angle", 0.0))
        d = float(j.get("distance", 0.0))
        out.append({"id": i, "link": common[0],
                    "at": [x1 + d * math.cos(turn), y1 + d * math.sin(turn)]})
    return out


def _inputs(r: _Reader, names: dict[str, str], frame: str, joints: list[dict[str, Any]],
            notes: list[str]) -> dict[str, Any]:
    """The [mechanism] table: the drivers as a driver or as inputs with their sweeps."""
    mechanism: dict[str, Any] = {"fixed": frame}
    drivers = [x for x in r.links if x["type"] in ("driver", "arc_driver")]
    at = {j["id"]: tuple(j["at"]) for j in joints}
    rates = [abs(float(x.get("angular_velocity", math.tau / 360)))
             for x in drivers]
    slowest = min((w for w in rates if w > 0), default=math.tau / 360)
    inputs: list[dict[str, Any]] = []
    for x, rate in zip(drivers, rates):
        link = names[x["id"]]
        motor = x.get("motor_joint") or next((i for i in x["joints"] if i in at
                                              and r.joints[i]["type"] == "ground"), None)
        where = f"link {x['id']!r}"
        if not isinstance(motor, str) or motor not in at:
            raise r.bad("a driver needs a motor joint on the ground", where)
        others = [i for i in x["joints"] if i != motor and i in at]
        if not others:
            raise r.bad("a driver needs a joint besides its motor joint", where)
        drawn = math.atan2(at[others[0]][1] - at[motor][1], at[others[0]][0] - at[motor][0])
        mine = [(j["id"], tuple(j["at"])) for j in joints if link in j["links"]]
        reference = line_direction(sorted(mine), motor)
        shift = math.degrees((reference if reference is not None else drawn) - drawn)
        initial = x.get("initial_angle")
        if isinstance(initial, (int, float)) and abs(math.remainder(
                initial - drawn, math.tau)) > 1e-9:
            notes.append(f"driver {x['id']!r}: initial_angle {initial:.6g} rad is not its "
                         f"drawn direction {drawn:.6g} rad; the drawn pose is kept")
        notes.append(f"driver {x['id']!r}: {rate:.6g} rad a step is pylinkage's sampling "
                     f"({math.tau / rate if rate else math.inf:.6g} steps a turn), not a "
                     f"speed; not carried")
        value = math.degrees(drawn) + shift
        if x["type"] == "arc_driver":
            low = math.degrees(float(x.get("arc_start", 0.0))) + shift
            high = math.degrees(float(x.get("arc_end", math.pi))) + shift
            inputs.append({"joint": motor, "from": low, "to": high})
        else:
            sign = -1.0 if float(x.get("angular_velocity", 1.0)) < 0 else 1.0
            inputs.append({"joint": motor, "from": value,
                           "to": value + sign * 360.0 * rate / slowest})
        mechanism.setdefault("driver", link)
    if len(drivers) == 1 and drivers[0]["type"] == "driver" and \
            inputs[0]["to"] > inputs[0]["from"]:
        return mechanism
    mechanism.pop("driver", None)
    if inputs:
        mechanism["inputs"] = inputs
    else:
        notes.append("no driver: imported as a chain with its frame fixed")
    return mechanism


def read_pylinkage(text: str, *, source: str = "<string>") -> Imported:
    """A pylinkage 1.3 mechanism (its JSON serialisation) as a chain file.

    Each pylinkage link is a link (links that share two joints or more are one rigid
    link), each ground, revolute and prismatic joint a joint (a prismatic joint an R pin
    on a block that slides in a P joint on the frame, called ``slider ID`` and ``ID
    guide``), each tracker a point of the link that holds its reference joints, the
    ground link the fixed link and each driver an input (a single crank turning
    forward: the ``driver``).

    Parameters
    ----------
    text : str
        The JSON text (``mechanism_to_json`` writes it).
    source : str, optional
        Where it came from, for the messages.

    Returns
    -------
    Imported
        The chain file and the notes: what could not be carried over.

    Raises
    ------
    InterchangeError
        Malformed JSON, an unknown joint or link type, a link that names no joint, a
        position that is not two numbers, no ground link; one line naming the part.
    ChainFileError
        When what it describes is not a valid chain.

    Examples
    --------
    >>> model = read_pylinkage('''{"name": "four-bar", "ground": "ground", "joints": [
    ...   {"id": "A", "type": "ground", "position": [0, 0]},
    ...   {"id": "B", "type": "revolute", "position": [0, 1]},
    ...   {"id": "C", "type": "revolute", "position": [3, 3]},
    ...   {"id": "D", "type": "ground", "position": [4, 0]}],
    ...  "links": [{"id": "ground", "type": "ground", "joints": ["A", "D"]},
    ...   {"id": "crank", "type": "driver", "joints": ["A", "B"], "motor_joint": "A",
    ...    "angular_velocity": 0.0174533, "initial_angle": 1.5707963267948966},
    ...   {"id": "coupler", "type": "link", "joints": ["B", "C"]},
    ...   {"id": "rocker", "type": "link", "joints": ["C", "D"]}]}''')
    >>> model.chain.links, model.chain.mechanism.driver
    (('ground', 'crank', 'coupler', 'rocker'), 'crank')
    """
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise InterchangeError(f"not JSON: {e.msg} (line {e.lineno}, column {e.colno})",
                               format="pylinkage", source=source, line=e.lineno) from None
    r = _Reader(data, source)
    notes: list[str] = []
    names, frame = _bodies(r, notes)
    joints, points = _structure(r, names, frame, notes)
    points += _trackers(r, names, joints, notes)
    mechanism = _inputs(r, names, frame, joints, notes)
    keys: dict[str, Any] = {"name": str(data.get("name") or "pylinkage mechanism"),
                            "notes": "Imported from pylinkage's JSON serialisation.",
                            "joints": joints}
    if points:
        keys["points"] = points
        mechanism["output"] = points[0]["id"]
    keys["mechanism"] = mechanism
    return imported(keys, notes, source=source)
