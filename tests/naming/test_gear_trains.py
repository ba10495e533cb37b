"""Names for the gear-train atlas (issue 39): the example trains found among the entries
by their rotation graph, whatever the numbering of their links."""

from pathlib import Path

from chaingraph.naming.gear_trains import gear_train_names
from chaingraph.structure.atlas.gears import gear_atlas

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_the_examples_name_their_entries():
    four = gear_atlas(4, 1)
    names = gear_train_names(four, folders=[EXAMPLES])
    # a wheel meshing with two others on one carrier: the simple and the reverted train
    assert sorted(names[0]) == ["Reverted gear train", "Simple gear train"]
    assert names[1] == []
    five = gear_train_names(gear_atlas(5, 1), folders=[EXAMPLES])
    assert sum(n == ["Compound gear train"] for n in five) == 1
    assert sum(map(len, five)) == 1
    # the housed epicyclic train (its housing idle) names nothing of five links, 2 dof
    assert gear_train_names(gear_atlas(5, 2), folders=[EXAMPLES]) == [[], [], []]


def test_the_catalog_is_the_default():
    assert len(gear_train_names(gear_atlas(4, 1))) == 2
