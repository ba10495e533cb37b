"""A synthesised mechanism's page shows its task: the [task] table and, drawn as the
synthesis draws it, the targets and a function generator's structural error."""

import dataclasses
import tomllib

import numpy as np
import pytest

import chaingraph
from chaingraph import DesignError
from chaingraph.files import dumps
from chaingraph.naming.catalog import catalog_path
from chaingraph.report.build import build_report
from chaingraph.synthesis import function
from chaingraph.synthesis.function_generation import structural_error

LOG10 = "log10-function-generator"


def test_the_catalog_s_function_generator_is_the_certified_design():
    """The catalog entry is what ``design function`` writes for its task (solution 1,
    so certified), and its structural error, solved again from the catalog file, is the
    design's."""
    entry = chaingraph.load(catalog_path(LOG10))
    table = entry.task
    best = function(function=table["function"], x=tuple(table["x"]),
                    swing=tuple(table["swing"]), solutions=1).solutions[0]
    designed = {j.id: j.at for j in best.mechanism.joints}
    for j in entry.joints:
        assert j.at == pytest.approx(designed[j.id], abs=1e-9)
    assert best.mechanism.task["start"] == pytest.approx(table["start"], abs=1e-12)
    curve = structural_error(entry)
    assert float(np.max(np.abs(curve.y))) == pytest.approx(best.error.max, rel=1e-9)
    assert curve.marks == pytest.approx(table["precision_x"])
    # zero at the precision points, to the solver's rounding
    at = np.interp(curve.marks, curve.x, curve.y)
    assert np.all(np.abs(at) < 1e-3)


def test_a_chain_without_a_function_task_has_no_structural_error():
    with pytest.raises(DesignError) as e:
        structural_error(chaingraph.load(catalog_path("four-bar-chain")))
    assert e.value.parameter == "task"


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """The report of the function generator, of the catalog's beam engine given a motion
    task (three poses of its connecting rod: its pin B and its angle), and of a
    chain without a task."""
    folder = tmp_path_factory.mktemp("tasks")
    four = chaingraph.load(catalog_path("beam-engine"))
    m = chaingraph.solve(four, start=60.0, stop=120.0, steps=2, summary=False)
    poses = [[round(float(m["x:B"][k]), 3), round(float(m["y:B"][k]), 3),
              round(float(m["angle:connecting rod"][k]), 3)] for k in range(3)]
    made = dataclasses.replace(four, name="Three poses", task={"kind": "motion",
                                                               "poses": poses})
    (folder / "three-poses.toml").write_text(dumps(made))
    out = folder / "report"
    result = build_report([catalog_path(LOG10), folder / "three-poses.toml",
                           catalog_path("four-bar-chain")], out, progress=None, workers=1)
    assert result.failures == []
    return out


def test_the_function_generator_s_page_shows_its_task(pages):
    text = (pages / f"{LOG10}.html").read_text()
    assert 'id="task"' in text and "Synthesis task" in text
    assert "log10(x)" in text and "1.06699; 1.5; 1.93301" in text
    assert f'src="img/{LOG10}-task.svg"' in text and "structural error" in text
    picture = (pages / "img" / f"{LOG10}-task.svg").read_text()
    assert "precision points" in picture and "structural error" in picture


def test_a_motion_generator_s_page_shows_its_poses(pages):
    text = (pages / "three-poses.html").read_text()
    assert 'id="task"' in text and "poses (x, y, degrees)" in text
    assert "small numbered frames" in text
    assert "; ".join(f"{v:g}" for v in made_poses(pages)[1]) in text
    assert (pages / "img" / "three-poses-task.svg").stat().st_size > 500


def test_a_chain_without_a_task_has_no_task_section(pages):
    text = (pages / "four-bar-chain.html").read_text()
    assert 'id="task"' not in text and "Synthesis task" not in text
    assert not (pages / "img" / "four-bar-chain-task.svg").exists()


def made_poses(pages):
    """The poses the motion task's file holds."""
    return tomllib.loads((pages.parent / "three-poses.toml").read_text())["task"]["poses"]
