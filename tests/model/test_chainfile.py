"""Loading chain files: the catalog, round trips, and every bad file of the contract."""

import math

import pytest

import chaingraph
from chaingraph import ChainFileError
from chaingraph.files import dumps, from_document, loads

from ..conftest import CATALOG, catalog_path, run_cli

FOUR_BAR = '''name = "four-bar"
[[joints]]
id = "A"
kind = "R"
links = ["frame", "crank"]
at = [0, 0]
[[joints]]
id = "B"
kind = "R"
links = ["crank", "coupler"]
at = [20.0, 34.64]
[[joints]]
id = "C"
kind = "R"
links = ["coupler", "rocker"]
at = [110, 79]
[[joints]]
id = "D"
kind = "R"
links = ["rocker", "frame"]
at = [100, 0]
'''


@pytest.mark.parametrize("path", CATALOG, ids=[p.stem for p in CATALOG])
def test_every_catalog_file_loads_and_round_trips(path):
    chain = chaingraph.load(path)
    assert chain.name and chain.notes and chain.family
    assert chain.source == str(path)
    assert loads(dumps(chain)) == chain
    assert chain.has_pose


def test_catalog_has_the_issue_entries():
    stems = {p.stem for p in CATALOG}
    assert {"three-link-locked-chain", "four-bar-chain", "five-link-chain",
            "six-link-two-ternary-joints", "watt-six-bar-chain", "stephenson-six-bar-chain",
            "single-slider-crank-chain", "double-slider-crank-chain",
            "quaternary-joint-chain", "cam-and-follower"} <= stems


def test_load_gives_pose_points_and_mechanism(write):
    path = write(FOUR_BAR + '''
[[points]]
id = "E"
link = "coupler"
at = [60, 90]
[mechanism]
fixed = "frame"
driver = "crank"
omega = 10
output = "rocker"
''')
    chain = chaingraph.load(path)
    assert chain.joint("B").at == (20.0, 34.64)
    assert chain.point("E").link == "coupler"
    m = chain.mechanism
    assert (m.fixed, m.driver, m.omega, m.output) == ("frame", "crank", 10.0, "rocker")
    assert chain.links == ("frame", "crank", "coupler", "rocker")


def test_link_joint_graph_and_views():
    chain = chaingraph.load(catalog_path("six-link-two-ternary-joints"))
    g = chain.graph
    assert g.degree[("joint", "T1")] == 3 and g.nodes[("joint", "T1")]["order"] == 3
    assert all(g.degree[("link", x)] == 2 for x in chain.links)
    # the link graph turns each ternary joint into a triangle of edges
    assert chain.link_graph.number_of_edges() == 3 + 3 + 3
    slider = chaingraph.load(catalog_path("single-slider-crank-chain"))
    s = slider.graph
    assert s.nodes[("joint", "S")]["guide"] == "frame"
    assert s.edges[("joint", "S"), ("link", "frame")]["role"] == "guide"
    assert s.edges[("joint", "S"), ("link", "crosshead")]["role"] == "block"


def test_contracted_graph():
    watt = chaingraph.load(catalog_path("watt-six-bar-chain"))
    c = watt.contracted_graph
    assert set(c.nodes) == {("link", "t1"), ("link", "t2")}
    runs = sorted(len(d["links"]) for _, _, d in c.edges(data=True))
    assert runs == [0, 2, 2]
    steph = chaingraph.load(catalog_path("stephenson-six-bar-chain")).contracted_graph
    assert sorted(len(d["links"]) for _, _, d in steph.edges(data=True)) == [1, 1, 2]
    four = chaingraph.load(catalog_path("four-bar-chain")).contracted_graph
    assert four.number_of_nodes() == 1 and four.number_of_edges() == 1


def test_chain_is_immutable():
    chain = chaingraph.load(catalog_path("four-bar-chain"))
    with pytest.raises(AttributeError):
        chain.name = "x"
    with pytest.raises(nx_frozen_error()):
        chain.graph.add_node("x")


def nx_frozen_error():
    import networkx as nx
    return nx.NetworkXError


def _joint_doc(**over):
    joint = {"id": "A", "kind": "R", "links": ["a", "b"]}
    joint.update(over)
    return joint


def _doc(joints=None, **top):
    doc = {"name": "x", "joints": joints if joints is not None else [
        _joint_doc(), _joint_doc(id="B", links=["b", "c"])]}
    doc.update(top)
    return doc


BAD_DOCUMENTS = {
    "unknown kind": (_doc([_joint_doc(kind="hinge")]), "joint 'A'", "unknown kind 'hinge'"),
    "one link": (_doc([_joint_doc(links=["a"])]), "joint 'A'", "at least two links"),
    "no links": (_doc([_joint_doc(links=[])]), "joint 'A'", "at least two links"),
    "link twice": (_doc([_joint_doc(links=["a", "b", "a"])]), "joint 'A'", "named twice"),
    "duplicate id": (_doc([_joint_doc(), _joint_doc(links=["b", "c"])]), "joint 'A'",
                     "duplicate joint id"),
    "P without axis": (_doc([_joint_doc(kind="P", at=[0, 0])]), "joint 'A'",
                       "a P joint with 'at' needs 'axis'"),
    "P without at": (_doc([_joint_doc(kind="P", axis=30.0)]), "joint 'A'",
                     "a P joint with 'axis' needs 'at'"),
    "P with three links": (_doc([_joint_doc(kind="P", axis=0, links=["a", "b", "c"])]),
                           "joint 'A'", "joins exactly two links"),
    "cam ternary": (_doc([_joint_doc(kind="cam", links=["a", "b", "c"])]), "joint 'A'",
                    "only R joints may be multiple"),
    "fixed names no link": (_doc(mechanism={"fixed": "ground"}), "[mechanism]",
                            "'fixed' names no link"),
    "driver names no link": (_doc(mechanism={"fixed": "a", "driver": "zz"}), "[mechanism]",
                             "'driver' names no link"),
    "driver is fixed": (_doc(mechanism={"fixed": "a", "driver": "a"}), "[mechanism]",
                        "'driver' is the fixed link"),
    "output names nothing": (_doc(mechanism={"fixed": "a", "output": "tool"}), "[mechanism]",
                             "'output' names no link, joint or point"),
    "fixed missing": (_doc(mechanism={"driver": "a"}), "[mechanism]", "missing required key 'fixed'"),
    "at one number": (_doc([_joint_doc(at=[1.0])]), "joint 'A'", "two finite numbers"),
    "at three numbers": (_doc([_joint_doc(at=[1, 2, 3])]), "joint 'A'", "two finite numbers"),
    "at text": (_doc([_joint_doc(at=["1", 2])]), "joint 'A'", "two finite numbers"),
    "at nan": (_doc([_joint_doc(at=[math.nan, 2])]), "joint 'A'", "two finite numbers"),
    "at inf": (_doc([_joint_doc(at=[math.inf, 2])]), "joint 'A'", "two finite numbers"),
    "at boolean": (_doc([_joint_doc(at=[True, 2])]), "joint 'A'", "two finite numbers"),
    "point at nan": (_doc(points=[{"id": "p", "link": "a", "at": [0, math.nan]}]), "point 'p'",
                     "two finite numbers"),
    "axis text": (_doc([_joint_doc(kind="P", at=[0, 0], axis="90")]), "joint 'A' key 'axis'",
                  "must be a number"),
    "axis inf": (_doc([_joint_doc(kind="P", at=[0, 0], axis=math.inf)]), "joint 'A' key 'axis'",
                 "finite"),
    "axis on R": (_doc([_joint_doc(axis=10)]), "joint 'A'", "only for P joints"),
    "missing name": ({"joints": [_joint_doc()]}, "key 'name'", "missing required key 'name'"),
    "name not text": (_doc(name=3), "key 'name'", "must be a string"),
    "empty name": (_doc(name="  "), "key 'name'", "non-empty"),
    "no joints key": ({"name": "x"}, "key 'joints'", "a chain needs at least one joint"),
    "empty joints": (_doc([]), "key 'joints'", "no joints"),
    "joints a table": (_doc(joints={"id": "A"}), "key 'joints'", "write [[joints]]"),
    "joint without id": (_doc([{"kind": "R", "links": ["a", "b"]}]), "joint #1",
                         "missing required key 'id'"),
    "joint without kind": (_doc([{"id": "A", "links": ["a", "b"]}]), "joint 'A'",
                           "missing required key 'kind'"),
    "links not a list": (_doc([_joint_doc(links="a, b")]), "joint 'A'", "array of link names"),
    "unknown top key": (_doc(jionts=[]), "key 'jionts'", "unknown key 'jionts'"),
    "unknown joint key": (_doc([_joint_doc(colour=3)]), "joint 'A'", "unknown key 'colour'"),
    "length key without lengths": (_doc([_joint_doc(angle=3)]), "joint 'A'",
                                   "add a [lengths] table"),
    "unknown space": (_doc(space="3d"), "key 'space'", "unknown space"),
    "spherical in plane": (_doc([_joint_doc(kind="spherical")]), "joint 'A'", "no planar form"),
    "cam in space": (_doc([_joint_doc(kind="cam")], space="spatial"), "joint 'A'",
                     "no spatial form"),
    "closure on lower pair": (_doc([_joint_doc(closure="force")]), "joint 'A'",
                              "lower pair is a closed pair"),
    "unknown closure": (_doc([_joint_doc(kind="cam", closure="glue")]), "joint 'A'",
                        "unknown closure"),
    "point on no link": (_doc(points=[{"id": "p", "link": "z", "at": [0, 0]}]), "point 'p'",
                         "names no link"),
    "point id clashes": (_doc(points=[{"id": "A", "link": "a", "at": [0, 0]}]), "point 'A'",
                         "duplicate id"),
    "point without at": (_doc(points=[{"id": "p", "link": "a"}]), "point 'p'",
                         "missing required key 'at'"),
    "omega zero": (_doc(mechanism={"fixed": "a", "omega": 0}), "[mechanism]", "non-zero"),
    "omega text": (_doc(mechanism={"fixed": "a", "omega": "fast"}), "[mechanism] key 'omega'",
                   "must be a number"),
    "mechanism not a table": (_doc(mechanism="frame"), "[mechanism]", "must be a table"),
}


@pytest.mark.parametrize("case", BAD_DOCUMENTS, ids=list(BAD_DOCUMENTS))
def test_bad_documents_name_what_and_where(case):
    doc, where, what = BAD_DOCUMENTS[case]
    with pytest.raises(ChainFileError) as info:
        from_document(doc, source="bad.toml")
    message = str(info.value)
    assert message.startswith("bad.toml: ")
    assert where in message and what in message
    assert info.value.source == "bad.toml"


def test_toml_syntax_error_gives_its_line(write):
    path = write('name = "x"\n[[joints]]\nid = "A"\nkind = R\n')
    with pytest.raises(ChainFileError) as info:
        chaingraph.load(path)
    assert info.value.line == 4
    assert "line 4" in str(info.value) and str(path) in str(info.value)


def test_unreadable_inputs(tmp_path, write):
    with pytest.raises(ChainFileError, match="no such file"):
        chaingraph.load(tmp_path / "missing.toml")
    with pytest.raises(ChainFileError, match="is a folder"):
        chaingraph.load(tmp_path)
    bad = tmp_path / "latin1.toml"
    bad.write_bytes('name = "caf\xe9"\n'.encode("latin-1"))
    with pytest.raises(ChainFileError, match="not UTF-8"):
        chaingraph.load(bad)


def test_errors_are_value_errors_with_fields():
    with pytest.raises(ValueError):
        from_document({"name": "x", "joints": [_joint_doc(kind="Z")]})
    try:
        from_document({"name": "x", "joints": [_joint_doc(kind="Z")]}, source="f.toml")
    except ChainFileError as e:
        assert (e.source, e.where) == ("f.toml", "joint 'A'") and "unknown kind" in e.problem


@pytest.mark.parametrize("case", ["unknown kind", "P without axis", "at nan", "fixed names no link"])
def test_cli_bad_file_exit_2_without_traceback(case, write):
    doc, where, what = BAD_DOCUMENTS[case]
    text = _to_toml(doc)
    path = write(text)
    code, out, err = run_cli("classify", path)
    assert code == 2
    assert "Traceback" not in err
    assert err.count("\n") == 1 and str(path) in err and where in err and what in err


def test_cli_syntax_error(write):
    path = write('name = "x"\n[[joints]\n')
    code, out, err = run_cli("classify", "--json", path)
    assert code == 2 and "line 2" in err and "Traceback" not in err and out == ""


def _to_toml(doc) -> str:
    """A tiny TOML writer for the test documents (top keys, joints, mechanism)."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, float) and math.isnan(v):
            return "nan"
        if isinstance(v, float) and math.isinf(v):
            return "inf" if v > 0 else "-inf"
        if isinstance(v, (int, float)):
            return repr(v)
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        return "[" + ", ".join(value(x) for x in v) + "]"
    lines = [f"{k} = {value(v)}" for k, v in doc.items() if not isinstance(v, (dict, list))
             or (isinstance(v, list) and not any(isinstance(x, dict) for x in v))]
    for key in ("joints", "points"):
        for t in doc.get(key, []) if isinstance(doc.get(key), list) else []:
            lines.append(f"[[{key}]]")
            lines += [f"{k} = {value(v)}" for k, v in t.items()]
    if isinstance(doc.get("mechanism"), dict):
        lines.append("[mechanism]")
        lines += [f"{k} = {value(v)}" for k, v in doc["mechanism"].items()]
    return "\n".join(lines) + "\n"


def test_the_one_toml_writer_writes_what_tomllib_reads():
    """Every catalog chain, and a document with tables, inline tables, quoted keys and
    arrays of tables, read back as written."""
    import tomllib

    from chaingraph.model.chainfile import chain_document, toml_text

    for path in CATALOG:
        chain = chaingraph.load(path)
        doc = chain_document(chain)
        back = tomllib.loads(toml_text(doc))
        assert back == json_like(doc), path.name
    doc = {"name": 'a "quoted" name', "lengths": {"slotted lever": 1.5, "crank": 40,
                                                  "plate": {"A-B": 1.0, "A-C": 2.0}},
           "assembly": {"C": "left", "plate": {"E": "right"}},
           "joints": [{"id": "A", "links": ["x", "y z"], "at": [0, -1e-17]}],
           "mechanism": {"inputs": [{"joint": "A", "at": 90.0}, "B"]}}
    assert tomllib.loads(toml_text(doc)) == json_like(doc)


def json_like(value):
    """Numbers as floats (the writer writes every number as one), tuples as lists."""
    if isinstance(value, dict):
        return {k: json_like(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_like(v) for v in value]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    return value
