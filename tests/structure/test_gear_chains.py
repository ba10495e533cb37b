"""The chain file of every train of the gear-train atlas (issue 39): read back, it is the
atlas's train (its graph's rotation key is the entry's, its turning pairs keep the
rules), its geometry holds (each meshing pair's axes are the sum of the pitch radii
apart, every gear has at least 12 teeth), and ``chaingraph gears`` solves it (the
Willis equations and the tabular method agree, every link turns at a speed fixed by the
driver). Four and five links fully, six links sampled, two freedoms sampled."""

import math
import re
from fractions import Fraction

import pytest

from chaingraph.files import loads
from chaingraph.kinematics.gears import train_speeds
from chaingraph.structure.atlas.gear_chains import MIN_TEETH, MODULE, gear_chain_text
from chaingraph.structure.atlas.gears import (
    chain_graph,
    gear_atlas,
    rotation_key,
    train_levels,
    train_verdict,
)

from ..conftest import run_cli

CASES = ([(4, 1, i) for i in range(2)] + [(5, 1, i) for i in range(6)]
         + [(6, 1, i) for i in range(0, 27, 4)] + [(6, 2, i) for i in (0, 5, 11)])


def _axis(chain, link, carrier):
    return next(j.at for j in chain.joints if j.kind == "R" and link in j.links
                and carrier in j.links)


@pytest.mark.parametrize("links, dof, i", CASES)
def test_the_file_is_the_train_and_its_geometry_holds(links, dof, i, tmp_path):
    entry = gear_atlas(links, dof)[i]
    text = gear_chain_text(entry, dof)
    chain = loads(text)
    names, turning, gears = chain_graph(chain)
    assert len(names) == links and len(gears) == links - 1 - dof
    assert rotation_key(links, gears) == rotation_key(links, entry.gears)
    assert train_verdict(links, turning, gears, dof=dof) is None
    assert max(train_levels(links, turning, gears)) == max(entry.levels)
    number = {x: int(x[1:]) - 1 for x in names}               # L1 is the atlas's link 0
    assert {tuple(sorted((number[names[a]], number[names[b]]))) for a, b in turning} == \
        set(entry.turning)
    for g in chain.gears:
        assert min(g.teeth) >= MIN_TEETH and not g.internal
        a, b = (_axis(chain, x, g.carrier) for x in g.links)
        assert math.isclose(math.dist(a, b), MODULE * sum(g.teeth) / 2)
    # solved: every link's speed fixed, the driver's and the fixed link's given
    m = chain.mechanism
    drive = re.findall(r"--speed (\S+)=1", chain.notes.split("Run:")[1])
    assert len(drive) == (0 if dof == 1 else dof)
    speeds = {x: Fraction(k + 1) for k, x in enumerate(drive or [m.driver])}
    result = train_speeds(chain, speeds=speeds)
    assert result.freedom == dof and set(result.speeds) == set(chain.links)
    for g in chain.gears:                      # Willis, again, with the file's teeth
        wa, wb, wc = (result.speeds[x] for x in (*g.links, g.carrier))
        assert (wa - wc) * g.teeth[0] == -(wb - wc) * g.teeth[1]
    path = tmp_path / "t.toml"
    path.write_text(text)
    code, out, err = run_cli("gears", path, *(a for x in drive for a in ("--speed", f"{x}=1")))
    assert code == 0, err
    assert out.startswith(f"{chain.name}: {m.fixed} fixed")
