"""Write the reference poses of the assembly tests (tests/kinematics/test_assembly.py):
the pose of every mechanism given by its lengths, and of every catalog and example
mechanism measured and assembled again.

    python tests/data/make_assembly_poses.py tests/data/assembly-poses.json

Run it at the commit whose poses are the reference (the poses before the assembly moved
onto the solver's kernels were written by it at 96a56ac).
"""

import glob
import json
import sys
import warnings
from pathlib import Path


def poses(root):
    import chaingraph
    from chaingraph.errors import ChainGraphError
    from chaingraph.kinematics.assembly import measure

    def pose(chain):
        return {"joints": {j.id: list(j.at) for j in chain.joints},
                "axes": {j.id: j.axis for j in chain.joints if j.kind == "P"},
                "points": {p.id: list(p.at) for p in chain.points}}
    out = {}
    files = sorted(glob.glob(str(root / "catalog/*.toml"))
                   + glob.glob(str(root / "examples/*.toml"))
                   + glob.glob(str(root / "tests/data/*.toml")))
    for f in files:
        name = Path(f).relative_to(root).as_posix()
        text = Path(f).read_text(encoding="utf-8")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            chain = chaingraph.load(f)
            if "[lengths]" in text:
                out[name] = pose(chain)
            elif chain.mechanism is not None and chain.has_pose:
                try:
                    out[name + " measured"] = pose(chaingraph.loads(measure(chain)))
                except ChainGraphError:
                    pass
    return out


if __name__ == "__main__":
    root = Path(__file__).resolve().parents[2]
    sys.path.insert(0, str(root))
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        json.dump(poses(root), f, indent=1, sort_keys=True)
