"""Groups of higher class are the least sets of links their equations determine (issue
35: a 20-link chain of dyads fixed at an outer link was one 18-link group, whose cycle
did not end in minutes), and solving them so gives the poses one Newton group gives."""

import itertools
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph.geometry import FIXED
from chaingraph.kinematics import build_plan, cycle
from chaingraph.kinematics.equations import constraint_rows
from chaingraph.kinematics.tracking import evaluate

DATA = Path(__file__).parents[1] / "data"


def _determined(links, known, constraints):
    """Whether the constraints among ``links`` and ``known`` fix every coordinate of
    ``links`` (full rank at the drawn pose, brute force)."""
    links = sorted(links)
    col = {x: 3 * i for i, x in enumerate(links)}
    pose = {x: FIXED for x in set(links) | set(known)}
    rows = []
    for c in constraints:
        if not ({c.a, c.b} <= set(links) | set(known)) or not ({c.a, c.b} & set(links)):
            continue
        for coef in constraint_rows(c, pose | ({c.drive: FIXED} if c.drive else {})):
            row = np.zeros(3 * len(links))
            for x, v in coef.items():
                if x in col:
                    row[col[x]:col[x] + 3] = v
            rows.append(row)
    return bool(rows) and np.linalg.matrix_rank(np.array(rows), tol=1e-9) == 3 * len(links)


@pytest.mark.parametrize("fixed, driver, size", [("L10", "L0", 4), ("L12", "L8", 8)])
def test_a_group_is_the_least_set_of_links_its_equations_determine(fixed, driver, size):
    chain = chaingraph.load(DATA / "dyad20.toml")
    plan = build_plan(chain, fixed, driver)
    kinds = [s.kind for s in plan.steps]
    assert kinds.count("group") == 1 and kinds[-1] == "dyad"   # closed forms go on after it
    i = kinds.index("group")
    group = plan.steps[i].links
    assert len(group) == size
    known = {fixed} | {x for s in plan.steps[:i] for x in s.links}
    assert _determined(group, known, plan.constraints)
    for k in range(1, len(group)):
        for part in itertools.combinations(group, k):
            assert not _determined(part, known, plan.constraints), part


def test_groups_solved_apart_give_the_poses_of_one_newton_group():
    chain = chaingraph.load(DATA / "dyad20.toml")
    split = build_plan(chain, "L10", "L0")
    whole = build_plan(chain, "L10", "L0", closed_form=False)
    assert [s.kind for s in whole.steps] == ["group"]
    c = cycle(split)
    theta = split.theta0 + np.linspace(0.0, 0.9 * (c.high - split.theta0), 12)
    e1, e2 = evaluate(split, theta), evaluate(whole, theta)
    assert e1.feasible.all() and e2.feasible.all()
    for link in chain.links:
        for j in range(3):
            assert np.allclose(np.broadcast_to(e1.pose[link][j], theta.shape),
                               np.broadcast_to(e2.pose[link][j], theta.shape),
                               atol=1e-9 * split.size), link
