"""Names for the gear-train atlas (issue 39): the catalog's trains found among the entries
by their rotation graph, whatever the numbering of their links."""

import json

from chaingraph.naming.catalog import catalog_dir
from chaingraph.naming.gear_trains import gear_train_names
from chaingraph.structure.atlas.gears import gear_atlas

from ..conftest import run_cli


def test_the_catalog_names_its_trains_in_the_atlas():
    names = gear_train_names(gear_atlas(4, 1))        # the catalog by default
    # a wheel meshing with two others on one carrier: the simple and the reverted train
    assert sorted(names[0]) == ["Reverted gear train", "Simple gear train"]
    assert names[1] == []
    five = gear_train_names(gear_atlas(5, 1))
    assert sum(n == ["Compound gear train"] for n in five) == 1
    assert sum(map(len, five)) == 1
    # the housed epicyclic train (its housing idle) names nothing of five links, 2 dof
    assert gear_train_names(gear_atlas(5, 2)) == [[], [], []]


def test_the_folders_given_replace_the_catalog(tmp_path):
    assert gear_train_names(gear_atlas(4, 1), folders=[tmp_path]) == [[], []]
    assert gear_train_names(gear_atlas(4, 1), folders=[catalog_dir()]) == \
        gear_train_names(gear_atlas(4, 1))


def test_atlas_gears_json_names_the_catalog_trains():
    named = {}
    for links in (4, 5):
        code, out, err = run_cli("atlas", "--gears", "--links", links, "--dof", 1, "--json")
        assert code == 0, err
        named[links] = {t["id"]: sorted(t["names"]) for t in json.loads(out)["trains"]
                        if t["names"]}
    assert named[4] == {1: ["Reverted gear train", "Simple gear train"]}
    assert list(named[5].values()) == [["Compound gear train"]]
