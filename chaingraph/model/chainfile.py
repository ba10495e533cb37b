"""Reading and writing chain files (TOML, the public format).

:func:`parse_file` reads a file, :func:`parse_text` a string, :func:`parse_document` an
already parsed document (a dict), each into a :class:`Document`: nothing is solved here
(:mod:`chaingraph.files` places it; that is ``chaingraph.load``). The keys and types are
checked here and the chain's meaning in :class:`~chaingraph.model.chain.Chain` itself, so the
catalog, a user's file and a chain built in Python are validated by the same code. Every
problem raises :class:`~chaingraph.errors.ChainFileError` naming the file, the joint or key, and what
is wrong. :func:`dumps` writes a chain back in the same format.
"""

from __future__ import annotations

import json
import math
import os
import re
import tomllib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, NoReturn

from chaingraph.errors import ChainFileError
from chaingraph.model.cams import Cam, cam_entry, read_cam
from chaingraph.model.chain import Chain, Input, Joint, LinkMass, Load, Mechanism, Point
from chaingraph.model.dimensions import Dimensions, parse_dimensions
from chaingraph.model.gears import GearPair, gear_entry, gear_pair
from chaingraph.model.values import LARGEST, Fail, number, shown, type_name

__all__ = ["Document", "parse_file", "file_bytes", "parse_text", "parse_document", "dumps", "save",
           "toml_text", "chain_document"]

TOP_KEYS = ("name", "family", "units", "space", "notes", "naming", "joints", "points",
            "mechanism", "lengths", "assembly", "links", "forces", "loads", "task",
            "cams", "gears")
JOINT_KEYS = ("id", "kind", "links", "at", "axis", "closure", "friction")
LINK_KEYS = ("name", "mass", "centre", "inertia")
FORCES_KEYS = ("gravity",)
LOAD_KEYS = ("on", "at", "force", "torque", "along", "table", "pressure", "area", "against",
             "cycle", "stroke", "resist")
POINT_KEYS = ("id", "link", "at")
MECHANISM_KEYS = ("fixed", "driver", "inputs", "omega", "output")
INPUT_KEYS = ("joint", "from", "to")
DIMENSION_JOINT_KEYS = ("offset", "angle", "block_offset", "block_angle", "near")


@dataclass(frozen=True)
class Document:
    """A chain file read and checked, not yet placed. ``chain`` is the chain as written:
    for a file of coordinates, its drawn pose as typed (drawing-level rounding is mended
    when it is placed); for a file given by lengths, its structure (points at the
    origin), with ``dimensions`` (:class:`~chaingraph.model.dimensions.Dimensions`: lengths,
    sliding lines, the inputs' values, modes, typed and rough positions) and the
    ``joints`` and ``points`` as written. :func:`chaingraph.files.load` places it."""

    chain: Chain
    dimensions: Dimensions | None = None
    joints: tuple[Joint, ...] = ()
    points: tuple[Point, ...] = ()


def file_bytes(path: str | os.PathLike[str], *, what: str = "chain file") -> bytes:
    """The bytes of the file at ``path``, or ChainFileError saying why not (no such
    file, a folder, not readable), ``what`` naming what the file should have been."""
    source = os.fspath(path)
    try:
        with open(source, "rb") as f:
            return f.read()
    except FileNotFoundError:
        raise ChainFileError("no such file", source=source) from None
    except IsADirectoryError:
        raise ChainFileError(f"is a folder, not a {what}", source=source) from None
    except OSError as e:
        raise ChainFileError(f"cannot be read ({e.strerror})", source=source) from None


def parse_file(path: str | os.PathLike[str]) -> Document:
    """The :class:`Document` of a chain file (reads, checks; solves nothing)."""
    source = os.fspath(path)
    raw = file_bytes(source)
    if raw[:2] in (b"\xff\xfe", b"\xfe\xff"):
        raise ChainFileError("is UTF-16 text (it starts with a UTF-16 byte-order mark): save "
                             "it as UTF-8", source=source)
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ChainFileError(f"is not UTF-8 text (byte {e.start})", source=source) from None
    return parse_text(text, source=source)


def parse_text(text: str, *, source: str = "<string>") -> Document:
    """The :class:`Document` of TOML text. A leading byte-order mark (as some editors
    save UTF-8) is read past."""
    return parse_document(_parse_toml(text.removeprefix("\ufeff"), source), source=source)


def _parse_toml(text: str, source: str) -> dict[str, Any]:
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        msg = str(e)
        m = re.search(r"\(at line (\d+), column (\d+)\)", msg)
        line = int(m.group(1)) if m else None
        text_line = text.splitlines()[line - 1] if line and line <= len(text.splitlines()) else ""
        spaced = re.match(r"\s*([A-Za-z0-9_-]+(?:[ \t]+[A-Za-z0-9_-]+)+)\s*=", text_line)
        if spaced:
            key = re.sub(r"\s+", " ", spaced.group(1))
            msg += (f": a key with a space must be quoted, as in \"{key}\" = ... "
                    "(link and joint names are keys in [lengths] and [assembly])")
        raise ChainFileError(f"TOML syntax error: {msg}", source=source, line=line) from None
    except ValueError as e:          # an integer past Python's 4,300-digit conversion limit
        raise ChainFileError(f"a number cannot be read ({str(e).split(':')[0]}); numbers "
                             f"must be at most {LARGEST:g} in size", source=source) from None
    except RecursionError:
        raise ChainFileError("arrays or tables nested too deeply (a chain file needs three "
                             "levels at most)", source=source) from None
    return doc


def parse_document(doc: dict[str, Any], *, source: str = "<document>") -> Document:
    """The :class:`Document` of a parsed TOML document (a dict): every key checked,
    nothing solved."""
    def fail(problem: str, where: str | None = None) -> NoReturn:
        raise ChainFileError(problem, source=source, where=where)

    if not isinstance(doc, dict):
        fail(f"a chain document is a table of keys, not {type_name(doc)}")
    _no_unknown_keys(doc, TOP_KEYS, None, fail)
    if "name" not in doc:
        fail("missing required key 'name'", "key 'name'")
    name = _string(doc["name"], "key 'name'", fail)
    family = _optional_string(doc, "family", "key 'family'", fail)
    units = _optional_string(doc, "units", "key 'units'", fail)
    notes = _optional_string(doc, "notes", "key 'notes'", fail)
    naming = _optional_string(doc, "naming", "key 'naming'", fail)
    space = _optional_string(doc, "space", "key 'space'", fail) or "planar"
    if "joints" not in doc:
        fail("missing [[joints]]: a chain needs at least one joint", "key 'joints'")
    dimensioned = "lengths" in doc
    joints = tuple(_joint(t, i, fail, dimensioned) for i, t in
                   enumerate(_tables(doc["joints"], "joints", fail)))
    points = tuple(_point(t, i, fail, dimensioned) for i, t in
                   enumerate(_tables(doc.get("points", []), "points", fail)))
    mechanism = None
    if "mechanism" in doc:
        mechanism = _mechanism(doc["mechanism"], fail, dimensioned="lengths" in doc)
    meta = dict(name=name, family=family, units=units, space=space, notes=notes,
                source=source, naming=naming, task=_task(doc, fail),
                **_masses_and_loads(doc, fail), cams=_cams(doc, joints, fail),
                gears=_gears(doc, mechanism, fail))
    if mechanism is not None and not dimensioned:
        kinds = {j.id: j.kind for j in joints}
        for i, item in enumerate(mechanism.inputs):
            if item.at is not None and kinds.get(item.joint) != "P":
                fail("'at' (the input's value in the drawn pose) is given by the drawing "
                     "for an R input; in a file of coordinates it is only for a P input "
                     "(the origin its slide is measured from), or add a [lengths] table",
                     f"[mechanism] inputs #{i + 1}")
    if "lengths" in doc:
        return _dimensioned(doc, joints, points, mechanism, meta, fail)
    if "assembly" in doc:
        fail("[assembly] chooses the assembly modes of a mechanism given by [lengths]; "
             "this file has none", "[assembly]")
    return Document(Chain(joints=joints, points=points, mechanism=mechanism, **meta))


def _dimensioned(doc: dict[str, Any], joints: tuple[Joint, ...], points: tuple[Point, ...],
                 mechanism: Mechanism | None, meta: dict[str, Any], fail: Fail) -> Document:
    """The document of a chain given by its dimensions: its structure and dimensions."""
    bare = tuple(Joint(j.id, j.kind, j.links, closure=j.closure, friction=j.friction)
                 for j in joints)
    # the points' places are found when it is placed; (0, 0) stands in meanwhile
    structure = Chain(joints=bare, mechanism=mechanism,
                      points=tuple(Point(p.id, p.link, (0.0, 0.0)) for p in points), **meta)
    point_links = [(p.id, p.link) for p in points]
    dims = parse_dimensions(doc, bare, point_links, fail)
    for j in joints:
        if j.axis is not None and j.kind != "P":
            fail("'axis' is only for P joints", f"joint {j.id!r}")
        if j.at is not None:
            if max(abs(v) for v in j.at) > 1e100:
                fail("'at' is too large to assemble with (coordinates at most 1e100)",
                     f"joint {j.id!r}")
            dims.typed[j.id] = j.at
        if j.axis is not None:
            dims.axes[j.id] = j.axis
    for p in points:
        if p.at is not None:
            dims.typed[p.id] = p.at
    for kind, tables in (("joint", doc.get("joints", [])), ("point", doc.get("points", []))):
        for t in tables:
            if "near" in t:
                dims.near[t["id"]] = _coordinates(t["near"], f"{kind} {t['id']!r} key 'near'",
                                                  fail)
    return Document(structure, dims, joints, points)


def _task(doc: dict[str, Any], fail: Fail) -> dict[str, Any] | None:
    """The ``[task]`` table, kept as read: what a synthesised mechanism was designed to
    do (``kind`` and its targets, see :mod:`chaingraph.synthesis`); nothing solves it."""
    if "task" not in doc:
        return None
    task = doc["task"]
    if not isinstance(task, dict):
        fail(f"[task] must be a table, not {type_name(task)}", "[task]")
    kind = task.get("kind")
    if not isinstance(kind, str) or not kind:
        fail("[task] needs 'kind', the kind of task (\"function\", \"path\" or "
             "\"motion\")", "[task]")
    return task


def _gears(doc: dict[str, Any], mechanism: Mechanism | None,
           fail: Fail) -> tuple[GearPair, ...]:
    """``[[gears]]``: the gear pairs as read (the chain checks their links and
    carriers); a pair without a carrier takes the fixed link."""
    fixed = mechanism.fixed if mechanism is not None else None
    return tuple(gear_pair(t, i, fixed, fail)
                 for i, t in enumerate(_tables(doc.get("gears", []), "gears", fail)))


def _no_unknown_keys(table: dict[str, Any], allowed: Sequence[str], where: str | None,
                     fail: Fail) -> None:
    for key in table:
        if key not in allowed:
            fail(f"unknown key {key!r} (allowed: {', '.join(allowed)})",
                 where or f"key {key!r}")


def _string(value: object, where: str, fail: Fail) -> str:
    if not isinstance(value, str):
        fail(f"must be a string, got {type_name(value)}", where)
    return value


def _optional_string(table: dict[str, Any], key: str, where: str, fail: Fail) -> str | None:
    return _string(table[key], where, fail) if key in table else None


#: the largest number a chain file may hold (a coordinate, a length, an angle, a speed):
#: beyond it, squares and products overflow or a float cannot hold a thousandth
def _coordinates(value: object, where: str, fail: Fail) -> tuple[float, float]:
    if (not isinstance(value, list) or len(value) != 2
            or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in value)):
        fail(f"'at' must be two finite numbers [x, y], got {shown(value)}", where)
    if any(isinstance(v, float) and not math.isfinite(v) for v in value):
        fail(f"'at' must be two finite numbers [x, y], got {shown(value)}", where)
    return (number(value[0], where + " 'at' x", fail), number(value[1], where + " 'at' y", fail))


def _tables(value: object, key: str, fail: Fail) -> list[dict[str, Any]]:
    if isinstance(value, dict):
        fail(f"'{key}' must be an array of tables: write [[{key}]] for each entry",
             f"key '{key}'")
    if not isinstance(value, list) or not all(isinstance(t, dict) for t in value):
        fail(f"'{key}' must be an array of tables ([[{key}]]), got {type_name(value)}",
             f"key '{key}'")
    return value


def _joint(table: dict[str, Any], index: int, fail: Fail, dimensioned: bool = False) -> Joint:
    label = f"joint #{index + 1}"
    if "id" in table and isinstance(table["id"], str) and table["id"]:
        label = f"joint {table['id']!r}"
    _no_unknown_keys(table, JOINT_KEYS + DIMENSION_JOINT_KEYS, None,
                     lambda problem, where: fail(problem, label))
    if not dimensioned:
        for key in DIMENSION_JOINT_KEYS:
            if key in table:
                fail(f"'{key}' belongs to a mechanism given by its lengths: add a "
                     "[lengths] table", label)
    for key in ("id", "kind", "links"):
        if key not in table:
            fail(f"missing required key '{key}'", label)
    joint_id = _string(table["id"], label + " key 'id'", fail)
    if not joint_id:
        fail("'id' must not be empty", label)
    kind = _string(table["kind"], label + " key 'kind'", fail)
    links = table["links"]
    if not isinstance(links, list) or not all(isinstance(x, str) for x in links):
        fail(f"'links' must be an array of link names, got {shown(links)}", label)
    at = _coordinates(table["at"], label, fail) if "at" in table else None
    axis = number(table["axis"], label + " key 'axis'", fail) if "axis" in table else None
    closure = _optional_string(table, "closure", label + " key 'closure'", fail)
    friction = (number(table["friction"], label + " key 'friction'", fail)
                if "friction" in table else None)
    return Joint(id=joint_id, kind=kind, links=tuple(links), at=at, axis=axis,
                 closure=closure, friction=friction)


def _pair(value: object, key: str, where: str, fail: Fail, unit: str) -> tuple[float, float]:
    if (not isinstance(value, list) or len(value) != 2
            or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in value)
            or any(isinstance(v, float) and not math.isfinite(v) for v in value)):
        fail(f"'{key}' must be two finite numbers ({unit}), got {shown(value)}", where)
    return (number(value[0], f"{where} '{key}' x", fail),
            number(value[1], f"{where} '{key}' y", fail))


def _masses_and_loads(doc: dict[str, Any], fail: Fail) -> dict[str, Any]:
    """``[[links]]``, ``[forces]`` and ``[[loads]]``: the Chain's masses, gravity, loads
    (their meaning, such as a link that exists, is checked by the Chain)."""
    masses = []
    for i, t in enumerate(_tables(doc.get("links", []), "links", fail)):
        where = f"[[links]] #{i + 1}"
        _no_unknown_keys(t, LINK_KEYS, None, lambda problem, w: fail(problem, where))
        for key in ("name", "mass"):
            if key not in t:
                fail(f"missing required key '{key}'", where)
        link = _string(t["name"], where + " key 'name'", fail)
        where = f"[[links]] {link!r}"
        mass = number(t["mass"], where + " key 'mass'", fail)
        centre = _pair(t["centre"], "centre", where, fail, "[x, y]") if "centre" in t else None
        inertia = number(t["inertia"], where + " key 'inertia'", fail) if "inertia" in t else 0.0
        masses.append(LinkMass(link, mass, centre, inertia))
    gravity = None
    if "forces" in doc:
        table = doc["forces"]
        if not isinstance(table, dict):
            fail(f"'forces' must be a table ([forces]), got {type_name(table)}", "[forces]")
        _no_unknown_keys(table, FORCES_KEYS, None, lambda problem, w: fail(problem, "[forces]"))
        if "gravity" in table:
            gravity = _pair(table["gravity"], "gravity", "[forces]", fail, "m/s^2")
    loads = [_load(t, f"[[loads]] #{i + 1}", fail)
             for i, t in enumerate(_tables(doc.get("loads", []), "loads", fail))]
    return {"masses": tuple(masses), "gravity": gravity, "loads": tuple(loads)}


def _cams(doc: dict[str, Any], joints: tuple[Joint, ...], fail: Fail) -> tuple[Cam, ...]:
    """``[[cams]]``: the chain's disc cams and followers (:mod:`chaingraph.model.cams`)."""
    cams = tuple(read_cam(t, i, joints, fail)
                 for i, t in enumerate(_tables(doc.get("cams", []), "cams", fail)))
    ids = [c.id for c in cams]
    for c in cams:
        if ids.count(c.id) > 1:
            fail("two cams have this id", f"[[cams]] {c.id!r}")
    return cams


def _load(t: dict[str, Any], where: str, fail: Fail) -> Load:
    """One ``[[loads]]`` table as a :class:`Load` (degrees read as radians); what it
    means, such as a P joint for ``along``, is checked by the Chain."""
    _no_unknown_keys(t, LOAD_KEYS, None, lambda problem, w: fail(problem, where))
    if "on" not in t:
        fail("missing required key 'on' (the link it acts on)", where)
    if not any(k in t for k in ("force", "torque", "table", "pressure", "resist")):
        fail("a load needs a 'force' [Fx, Fy] (N), a 'torque' (N m or \"mean\"), a "
             "'table' or 'pressure' along a P joint, or a 'resist' force (N)", where)
    on = _string(t["on"], where + " key 'on'", fail)
    at = _optional_string(t, "at", where + " key 'at'", fail)
    force = _pair(t["force"], "force", where, fail, "[Fx, Fy] in N") if "force" in t else None
    torque: float | str = 0.0
    if "torque" in t:
        torque = ("mean" if t["torque"] == "mean"
                  else number(t["torque"], where + " key 'torque' (N m or \"mean\")", fail))
    against = _string(t["against"], where + " key 'against'", fail) if "against" in t \
        else "slide"
    scale = math.radians(1.0) if against == "input" else 1.0
    tables = {}
    for key, unit in (("table", "N"), ("pressure", "Pa")):
        if key in t:
            rows = t[key]
            if not isinstance(rows, list) or not rows:
                fail(f"'{key}' must be a list of [x, {unit}] pairs, got {shown(rows)}", where)
            pairs = [_pair(r, key, f"{where} row {k + 1}", fail, f"[x, {unit}]")
                     for k, r in enumerate(rows)]
            tables[key] = tuple((x * scale, v) for x, v in pairs)
    cycle = None
    if "cycle" in t:
        cycle = math.radians(number(t["cycle"], where + " key 'cycle' (degrees)", fail))
    return Load(on, at, force, torque,
                along=_optional_string(t, "along", where + " key 'along'", fail),
                table=tables.get("table"), pressure=tables.get("pressure"),
                area=number(t["area"], where + " key 'area'", fail) if "area" in t else None,
                against=against, cycle=cycle,
                stroke=_optional_string(t, "stroke", where + " key 'stroke'", fail),
                resist=number(t["resist"], where + " key 'resist'", fail) if "resist" in t
                else None)


def _point(table: dict[str, Any], index: int, fail: Fail, dimensioned: bool = False) -> Point:
    label = f"point #{index + 1}"
    if "id" in table and isinstance(table["id"], str) and table["id"]:
        label = f"point {table['id']!r}"
    _no_unknown_keys(table, POINT_KEYS + ("near",), None,
                     lambda problem, where: fail(problem, label))
    if "near" in table and not dimensioned:
        fail("'near' belongs to a mechanism given by its lengths: add a [lengths] table",
             label)
    for key in POINT_KEYS:
        if key not in table and not (key == "at" and dimensioned):
            fail(f"missing required key '{key}'", label)
    point_id = _string(table["id"], label + " key 'id'", fail)
    link = _string(table["link"], label + " key 'link'", fail)
    at = _coordinates(table["at"], label, fail) if "at" in table else None
    return Point(id=point_id, link=link, at=at)


def _mechanism(table: object, fail: Fail, dimensioned: bool = False) -> Mechanism:
    where = "[mechanism]"
    if not isinstance(table, dict):
        fail(f"'mechanism' must be a table ([mechanism]), got {type_name(table)}", where)
    _no_unknown_keys(table, MECHANISM_KEYS + ("at",), None,
                     lambda problem, w: fail(problem, where))
    if "at" in table and not dimensioned:
        fail("'at' (the input's value in the drawn pose) belongs to a mechanism given by "
             "its lengths: add a [lengths] table", where)
    if "fixed" not in table:
        fail("missing required key 'fixed' (the fixed link)", where)
    fixed = _string(table["fixed"], where + " key 'fixed'", fail)
    driver = _optional_string(table, "driver", where + " key 'driver'", fail)
    output = _optional_string(table, "output", where + " key 'output'", fail)
    omega = number(table["omega"], where + " key 'omega'", fail) if "omega" in table else 1.0
    inputs = _inputs(table["inputs"], fail, dimensioned) if "inputs" in table else ()
    return Mechanism(fixed=fixed, driver=driver, omega=omega, output=output, inputs=inputs)


def _inputs(value: object, fail: Fail, dimensioned: bool = False) -> tuple[Input, ...]:
    """``inputs = ["A", {joint = "E", from = 110.0, to = 50.0}, ...]``"""
    where = "[mechanism] key 'inputs'"
    if not isinstance(value, list) or not value:
        fail("'inputs' must be a non-empty array of joint ids or tables "
             f"{{joint, from, to}}, got {shown(value)}", where)
    out = []
    for i, item in enumerate(value):
        here = f"[mechanism] inputs #{i + 1}"
        if isinstance(item, str):
            out.append(Input(_string(item, here, fail)))
            continue
        if not isinstance(item, dict):
            fail(f"an input must be a joint id or a table {{joint, from, to}}, "
                 f"got {type_name(item)}", here)
        _no_unknown_keys(item, INPUT_KEYS + ("at",), None,
                         lambda problem, w: fail(problem, here))
        if "joint" not in item:
            fail("missing required key 'joint'", here)
        joint = _string(item["joint"], here + " key 'joint'", fail)
        start = number(item["from"], here + " key 'from'", fail) if "from" in item else None
        stop = number(item["to"], here + " key 'to'", fail) if "to" in item else None
        at = number(item["at"], here + " key 'at'", fail) if "at" in item else None
        out.append(Input(joint, start, stop, None if dimensioned else at))
    return tuple(out)


# -- writing ------------------------------------------------------------------------
def toml_string(s: str) -> str:
    return json.dumps(s, ensure_ascii=False).replace("\x7f", "\\u007F")


def toml_number(x: float) -> str:
    x = float(x)
    if x == int(x) and abs(x) < 1e15:
        return f"{x:.1f}"
    return repr(x)


def toml_key(name: str) -> str:
    """A key as TOML writes it: bare when it can be, else quoted."""
    bare = bool(name) and name.isascii() and all(ch.isalnum() or ch in "_-" for ch in name)
    return name if bare else toml_string(name)


def _toml_value(value: Any) -> str:
    if isinstance(value, str):
        return toml_string(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return toml_number(value)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{toml_key(k)} = {_toml_value(v)}"
                               for k, v in value.items()) + "}"
    return "[" + ", ".join(_toml_value(v) for v in value) + "]"


def toml_text(document: dict[str, Any]) -> str:
    """The one TOML writer: a chain file's document (a dict as :mod:`tomllib` reads
    one) as text, keys in the document's order. A dict value is a table (``[name]``), a
    list of dicts an array of tables (``[[name]]``), anything else a value; inside
    them, dicts and lists are written inline. Numbers are written as floats.

    Examples
    --------
    >>> print(toml_text({"name": "x", "lengths": {"crank": 40, "slotted lever": 2.5},
    ...                  "joints": [{"id": "A", "at": [0, 1]}]}))
    name = "x"
    <BLANKLINE>
    [lengths]
    crank = 40.0
    "slotted lever" = 2.5
    <BLANKLINE>
    [[joints]]
    id = "A"
    at = [0.0, 1.0]
    <BLANKLINE>
    """
    def table(d: dict[str, Any]) -> list[str]:
        return [f"{toml_key(k)} = {_toml_value(v)}" for k, v in d.items()]
    top = {k: v for k, v in document.items() if not _is_table(v)}
    lines = table(top)
    for key, value in document.items():
        if isinstance(value, dict):
            lines += ["", f"[{toml_key(key)}]", *table(value)]
        elif _is_table(value):
            for item in value:
                lines += ["", f"[[{toml_key(key)}]]", *table(item)]
    return "\n".join(lines) + "\n"


def _is_table(value: object) -> bool:
    return isinstance(value, dict) or (isinstance(value, (list, tuple)) and bool(value)
                                       and all(isinstance(v, dict) for v in value))


def chain_document(chain: Chain) -> dict[str, Any]:
    """The chain as a chain file's document (the dict :func:`toml_text` writes)."""
    doc: dict[str, Any] = {"name": chain.name}
    for key in ("family", "units", "notes", "naming"):
        if getattr(chain, key) is not None:
            doc[key] = getattr(chain, key)
    if chain.space != "planar":
        doc["space"] = chain.space
    joints = []
    gear_joints = {g.id for g in chain.gears}
    for j in chain.joints:
        if j.id in gear_joints:          # written as its [[gears]] table
            continue
        item: dict[str, Any] = {"id": j.id, "kind": j.kind, "links": list(j.links)}
        if j.at is not None:
            item["at"] = list(j.at)
        if j.axis is not None:
            item["axis"] = j.axis
        if j.closure is not None:
            item["closure"] = j.closure
        if j.friction is not None:
            item["friction"] = j.friction
        joints.append(item)
    if joints:
        doc["joints"] = joints
    if chain.points:
        doc["points"] = [{"id": p.id, "link": p.link,
                          **({"at": list(p.at)} if p.at is not None else {})}
                         for p in chain.points]
    m = chain.mechanism
    if m is not None:
        mech: dict[str, Any] = {"fixed": m.fixed}
        if m.driver is not None:
            mech["driver"] = m.driver
        if m.inputs:
            mech["inputs"] = [_input_entry(i) for i in m.inputs]
        if m.omega != 1.0:
            mech["omega"] = m.omega
        if m.output is not None:
            mech["output"] = m.output
        doc["mechanism"] = mech
    if chain.masses:
        doc["links"] = [{"name": x.link, "mass": x.mass,
                         **({"centre": list(x.centre)} if x.centre is not None else {}),
                         **({"inertia": x.inertia} if x.inertia else {})}
                        for x in chain.masses]
    if chain.gravity is not None:
        doc["forces"] = {"gravity": list(chain.gravity)}
    if chain.loads:
        doc["loads"] = [load_entry(x) for x in chain.loads]
    if chain.cams:
        doc["cams"] = [cam_entry(c) for c in chain.cams]
    if chain.task is not None:
        doc["task"] = chain.task
    if chain.gears:
        doc["gears"] = [gear_entry(g) for g in chain.gears]
    return doc


def load_entry(load: Load) -> dict[str, Any]:
    """A :class:`Load` as its ``[[loads]]`` table (radians written as degrees)."""
    def degrees(v: float) -> float:
        return round(math.degrees(v), 9)
    scale = degrees if load.against == "input" else (lambda v: v)
    out: dict[str, Any] = {"on": load.on}
    for key in ("at", "along"):
        if getattr(load, key) is not None:
            out[key] = getattr(load, key)
    if load.force is not None:
        out["force"] = list(load.force)
    if load.torque:
        out["torque"] = load.torque
    for key in ("table", "pressure"):
        rows = getattr(load, key)
        if rows is not None:
            out[key] = [[scale(x), v] for x, v in rows]
    if load.area is not None:
        out["area"] = load.area
    if load.against != "slide":
        out["against"] = load.against
    if load.cycle is not None:
        out["cycle"] = degrees(load.cycle)
    for key in ("stroke", "resist"):
        if getattr(load, key) is not None:
            out[key] = getattr(load, key)
    return out


def dumps(chain: Chain) -> str:
    """The chain as TOML text in the public format; :func:`loads` reads it back.

    Examples
    --------
    >>> from chaingraph.model.chain import Chain, Joint
    >>> from chaingraph.model.chainfile import dumps, parse_text
    >>> c = Chain("pair", (Joint("A", "R", ("a", "b"), at=(0.0, 1.5)),))
    >>> print(dumps(c))
    name = "pair"
    <BLANKLINE>
    [[joints]]
    id = "A"
    kind = "R"
    links = ["a", "b"]
    at = [0.0, 1.5]
    <BLANKLINE>
    >>> parse_text(dumps(c)).chain == c
    True
    """
    return toml_text(chain_document(chain))


def _input_entry(item: Input) -> str | dict[str, Any]:
    if item.start is None and item.at is None:
        return item.joint
    entry: dict[str, Any] = {"joint": item.joint}
    if item.start is not None:
        entry.update({"from": item.start, "to": item.stop})
    if item.at is not None:
        entry["at"] = item.at
    return entry


def save(chain: Chain, path: str | os.PathLike[str]) -> None:
    """Write the chain to a TOML file (see :func:`dumps`)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(dumps(chain))
