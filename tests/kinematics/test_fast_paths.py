"""The solve's shortcuts give what the long way gives: a dyad's joints as the rates'
solve found them, a whole turn's last row as its first, the summary's few cubics in
floats, a plan's hash worked out once."""

import pickle
from dataclasses import replace

import numpy as np
import pytest

import chaingraph
from chaingraph.kinematics import summary
from chaingraph.kinematics.columns import LinkStates, point_of_states
from chaingraph.naming.catalog import catalog_path

#: catalog mechanisms with an RRR dyad: a crank-rocker, a parallelogram (dead centres:
#: its rates are NaN there), a six-bar
DYADS = ["beam-engine", "coupling-rod-of-a-locomotive", "watt-i-mechanism"]


@pytest.mark.parametrize("name", DYADS)
def test_a_dyad_s_joints_are_what_their_links_motion_gives(name):
    m = chaingraph.solve(chaingraph.load(catalog_path(name)), steps=720, summary=False)
    plan, states = m.plan, m.states
    assert states.points, "the rates' solve went through the dyad's joints"
    long_way = LinkStates(states.tau, states.pose, states.velocity, states.acceleration)
    size = plan.size
    for joint in m.joints:
        got, want = point_of_states(plan, states, joint), point_of_states(plan, long_way, joint)
        for field in ("x", "y", "vx", "vy", "ax", "ay"):
            a, b = getattr(got, field), getattr(want, field)
            assert np.array_equal(np.isnan(a), np.isnan(b)), (joint, field)
            scale = max(size, np.nanmax(np.abs(b), initial=0.0))
            assert np.nanmax(np.abs(a - b), initial=0.0) <= 1e-12 * scale, (joint, field)


def test_no_joint_shares_an_array_with_another_or_with_a_link_s_rates():
    m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=90, summary=False)
    joints = [getattr(p, f) for p in m.joints.values() for f in ("vx", "vy", "ax", "ay")]
    rates = {id(v) for table in (m.states.velocity, m.states.acceleration)
             for entry in table.values() for v in entry}
    assert len({id(v) for v in joints}) == len(joints)
    assert not rates & {id(v) for v in joints}


@pytest.mark.parametrize("name", ["beam-engine", "reciprocating-engine"])
def test_a_whole_turn_s_last_row_is_its_first(name):
    m = chaingraph.solve(chaingraph.load(catalog_path(name)), steps=3600)
    for column, values in m.columns.items():
        if column == "theta":
            continue
        first, last = values[0], values[-1]
        if column.startswith("angle:"):       # continuous over the turn: a turn on
            assert abs(np.remainder(last - first + 180.0, 360.0) - 180.0) < 1e-9, column
        else:
            assert last == first or np.isnan(last) and np.isnan(first), column


def test_the_few_cubics_solved_in_floats_are_the_arrays_ones():
    rng = np.random.default_rng(7)
    t0 = rng.uniform(0.0, 300.0, 6)
    t1 = t0 + rng.uniform(0.01, 2.0, 6)
    f0 = rng.uniform(0.1, 2.0, 6)
    f1 = -rng.uniform(0.1, 2.0, 6)
    g0, g1 = rng.normal(size=6), rng.normal(size=6)
    few = summary._cubic_roots(t0, t1, f0, f1, g0, g1)
    many = summary._cubic_roots(*(np.tile(v, 2) for v in (t0, t1, f0, f1, g0, g1)))[:6]
    assert np.array_equal(few, many)
    assert np.all((few >= t0) & (few <= t1))


def test_a_plan_s_hash_is_the_fields_and_is_not_pickled():
    plan = chaingraph.build_plan(chaingraph.load(catalog_path("beam-engine")))
    h = hash(plan)
    again = pickle.loads(pickle.dumps(plan))
    assert "_hash" not in again.__dict__ and again == plan and hash(again) == h
    moved = replace(plan, theta0=(plan.theta0 or 0.0) + 1.0)
    assert moved != plan and "_hash" not in moved.__dict__
