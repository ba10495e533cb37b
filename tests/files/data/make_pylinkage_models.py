"""Write the pylinkage models of tests/files/data as pylinkage 1.3 writes them, with the
joints' positions pylinkage's own simulation gives every 30 degrees (run inside pylinkage's
venv: benchmarks/.venv-pylinkage/bin/python tests/files/data/make_pylinkage_models.py).

Each model is built with pylinkage's MechanismBuilder (or its factories) and saved by
mechanism_to_dict; MODEL.trace.json holds, every 30 steps of one degree over a turn of
the crank, every joint's position as pylinkage steps it: what tests/files/test_pylinkage.py
compares chaingraph's solve with. Also the six-bar factories of pylinkage.synthesis
(watt_from_lengths, stephenson_from_lengths), converted by pylinkage's to_mechanism,
as the docs run them through import.
"""
import importlib.util
import json
import math
import sys
import types
from pathlib import Path

import pylinkage
from pylinkage.dyads._conversion import to_mechanism
from pylinkage.mechanism import MechanismBuilder, fourbar, slider_crank
from pylinkage.mechanism.serialization import mechanism_from_dict, mechanism_to_dict

# pylinkage.synthesis's __init__ needs scipy for its other modules; the two factories'
# module does not: load it alone
_package = types.ModuleType("pylinkage.synthesis")
_package.__path__ = [str(Path(pylinkage.__file__).parent / "synthesis")]
sys.modules.setdefault("pylinkage.synthesis", _package)
_spec = importlib.util.find_spec("pylinkage.synthesis.conversion")
_conversion = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_conversion)
stephenson_from_lengths = _conversion.stephenson_from_lengths
watt_from_lengths = _conversion.watt_from_lengths

HERE = Path(__file__).resolve().parent
STEP = math.radians(1.0)
EVERY = 30                      # steps between the positions kept


def watt():
    """Watt I: the four-bar A B C D whose coupler B C E and rocker D C F... the two
    ternary links (coupler B-C-E, rocker C-D-F) joined at C, and the dyad E G F."""
    b = MechanismBuilder(name="Watt six-bar")
    b.add_ground_link("ground", ports={"A": (0.0, 0.0), "D": (80.0, 0.0)})
    b.add_driver_link("crank", length=25.0, motor_port="A", omega=STEP,
                      initial_angle=math.radians(60.0))
    b.add_ternary_link("coupler", port_geometry={"0": (0.0, 0.0), "1": (85.0, 0.0),
                                                 "2": (40.0, 45.0)})
    b.add_ternary_link("rocker", port_geometry={"0": (0.0, 0.0), "1": (70.0, 0.0),
                                                "2": (20.0, -40.0)})
    b.add_link("link 5", length=70.0)
    b.add_link("link 6", length=60.0)
    b.connect("crank.tip", "coupler.0")
    b.connect("coupler.1", "rocker.0")
    b.connect("rocker.1", "ground.D")
    b.connect("coupler.2", "link 5.0")
    b.connect("link 5.1", "link 6.0")
    b.connect("link 6.1", "rocker.2")
    b.add_point_tracker("P", "link 5.0", "link 5.1", distance=35.0, angle=0.5)
    return b.build()


def stephenson():
    """A Stephenson six-bar: its two ternary links, the coupler (pins at the crank, the
    rocker and link 5) and the frame (pivots A, D, G), are not joined directly; the
    crank and the rocker on the frame, links 5 and 6 from the coupler back to G."""
    b = MechanismBuilder(name="Stephenson six-bar")
    b.add_ground_link("ground", ports={"A": (0.0, 0.0), "D": (90.0, 0.0),
                                       "G": (40.0, -70.0)})
    b.add_driver_link("crank", length=28.0, motor_port="A", omega=STEP,
                      initial_angle=math.radians(75.0))
    b.add_ternary_link("coupler", port_geometry={"0": (0.0, 0.0), "1": (90.0, 0.0),
                                                 "2": (30.0, -45.0)})
    b.add_link("rocker", length=60.0)
    b.add_link("link 5", length=55.0)
    b.add_link("link 6", length=50.0)
    b.connect("crank.tip", "coupler.0")
    b.connect("coupler.1", "rocker.0")
    b.connect("rocker.1", "ground.D")
    b.connect("coupler.2", "link 5.0")
    b.connect("link 5.1", "link 6.0")
    b.connect("link 6.1", "ground.G")
    return b.build()


MODELS = {
    "pylinkage-four-bar": lambda: fourbar(crank=30.0, coupler=90.0, rocker=70.0,
                                          ground=80.0, omega=STEP,
                                          initial_angle=math.radians(40.0)),
    "pylinkage-slider-crank": lambda: slider_crank(
        crank=30.0, rod=100.0, omega=STEP, initial_angle=math.radians(20.0),
        slide_through=(0.0, 15.0), slide_direction=(1.0, 0.25)),
    "pylinkage-watt": watt,
    "pylinkage-stephenson": stephenson,
}
FACTORIES = {
    "pylinkage-watt-factory": lambda: to_mechanism(watt_from_lengths(
        crank=1.5, coupler1=4.0, rocker1=3.5, link4=3.0, link5=2.5, rocker2=3.0,
        ground_length=6.0)),
    "pylinkage-stephenson-factory": lambda: to_mechanism(stephenson_from_lengths(
        crank=0.8, coupler=3.5, rocker=3.0, link4=2.0, link5=2.5, link6=3.0,
        ground_length=4.0)),
}


def trace(data):
    """Every joint's position every EVERY steps over a turn, as pylinkage steps the
    model. Its trackers are put by their own rule (TrackerJoint.update_position) on the
    joints pylinkage steps without them: with a tracker, pylinkage 1.3 leaves its Assur
    group solver for a joint-by-joint one that, on the Watt six-bar, takes a joint's
    old position as an anchor and stretches the rocker (|CD| 70 becomes 58.4 at 30
    degrees)."""
    trackers = [j for j in data["joints"] if j["type"] == "tracker"]
    bare = mechanism_from_dict({**data, "joints": [j for j in data["joints"]
                                                   if j["type"] != "tracker"]})
    ids = [j.id for j in bare.joints]
    rows = [[list(j.position) for j in bare.joints]]
    for k, coords in enumerate(bare.step(iterations=360), start=1):
        if k % EVERY == 0:
            rows.append([list(c) for c in coords])
    for t in trackers:
        joint = mechanism_from_dict({**data, "joints": [t], "links": []}).joints[0]
        for row in rows:
            joint.update_position(tuple(row[ids.index(t["ref_joint1_id"])]),
                                  tuple(row[ids.index(t["ref_joint2_id"])]))
            row.append(list(joint.position))
        ids.append(t["id"])
    return {"joints": ids, "step_deg": EVERY * math.degrees(STEP), "positions": rows}


def main():
    for stem, make in {**MODELS, **FACTORIES}.items():
        data = mechanism_to_dict(make())
        (HERE / f"{stem}.json").write_text(json.dumps(data, indent=2) + "\n")
        if stem not in FACTORIES:
            (HERE / f"{stem}.trace.json").write_text(json.dumps(trace(data)) + "\n")
            print(stem, len(data["joints"]), "joints")


if __name__ == "__main__":
    main()
