"""A pick is planned where the tree leaves its object before it: where the NextObject on its
own path found it (not one in another branch of a WeightedRandom, which has not run), or
where an earlier put-down of it left it. A palletizing cell of a user (#26) had validate
say a carton put on the QC table was "1.81-2.21 m away" on the pallet, and a pick at the
belt's end plan the pallet's cartons (the other branch's NextObject)."""

import dataclasses

import pytest

from tests.corpus.corpus_helpers import assert_one_line_error, expected_place, write_workspace
from tests.corpus.test_bad_cells import CASES, OBJECTS, PART_ON_TABLE, person

OTHER_TABLE = (
    "human:\n",
    "  - add_model: {name: other_table, file: package://hrc_drake_models/cell/work_table.sdf}\n"
    "  - add_weld: {parent: world, child: other_table::body, X_PC: {translation: [2.2, 0.7, 0]}}\n"
    "human:\n",
)
"""A second work table, 2.2 m along x from the corpus's."""
FRONTS = (
    "locations:\n",
    "locations:\n"
    "  table_front: {translation: [0.0, 1.45, 0.0], rotation: !Rpy {deg: [0, 0, -90]}}\n"
    "  other_front: {translation: [2.2, 1.45, 0.0], rotation: !Rpy {deg: [0, 0, -90]}}\n",
)
PARTS = (
    "safety:\n",
    f"{OBJECTS}{PART_ON_TABLE}    - {{type: part, pose: {{translation: [2.2, 0.6, 0.93]}}}}\n"
    "safety:\n",
)
"""A part on each table, 2.36 m from where the person stands at the other."""
OTHER = ("areas:\n", "areas:\n  other: [[1.6, 0.3], [2.8, 0.3], [2.8, 1.1], [1.6, 1.1]]\n")
TAKE = (
    '<ActorMovement target="table_front"/>\n'
    '      <NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>\n'
    '      <ActorPick object_id="{p}"/>\n'
)


def put_down_then(then: str):
    """The part taken off the table, put down on the other one, `then` taken again."""
    return TAKE + (
        '      <ActorCarry target="other_front"/>\n'
        '      <ActorPlace target="1.9;0.95;0.98"/>\n'
        f"      {then}\n"
        '      <ActorPick name="again" object_id="{p}"/>'
    )


def either_table(second_stand: str):
    """A WeightedRandom: the part off the table, or (standing at `second_stand`) off the
    other table, both written to {p}."""
    return (
        '<WeightedRandom weights="1;1">\n'
        f"      <Sequence>{TAKE}</Sequence>\n"
        f'      <Sequence><ActorMovement target="{second_stand}"/>\n'
        '      <NextObject area="other" filter="type=part" object_id="{p}" pose="{at}"/>\n'
        '      <ActorPick name="other" object_id="{p}"/></Sequence>\n'
        "      </WeightedRandom>"
    )


def case(tree: str, says=(), at="ActorPick"):
    return person(
        '<ActorMovement target="door"/>\n      <ActorAnimation animation_name="wave"/>',
        tree,
        says,
        at,
        changes=[OTHER_TABLE, FRONTS, PARTS, OTHER],
    )


FINE = {
    "a pick of what the tree has put down, where it was put": put_down_then(
        '<ActorAnimation animation_name="wave"/>'
    ),
    "a pick after its own branch's NextObject": either_table("other_front"),
    "a pick of what a Fallback makes where the part it looks for lies at the start": (
        '<ActorMovement target="table_front"/>\n'
        "      <Fallback>\n"
        '        <NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>\n'
        '        <SpawnObject type="part" pose="0.0;0.6;0.93" object_id="{p}"/>\n'
        "      </Fallback>\n"
        '      <ActorPick object_id="{p}"/>'
    ),
}


@pytest.mark.parametrize("name", FINE)
def test_a_pick_where_the_tree_has_left_its_object_is_not_judged_elsewhere(
    name, tmp_path, hrc_drake
):
    """The code before said the part lay 2.36 m away (on the first table) for the first two;
    for the third, that the part made where the one found lies would go into it (a user's
    restocking SpawnObject runs only when the NextObject before it finds none)."""
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, case(FINE[name])))
    assert status == 0, err


TOO_FAR = {
    "a pick of what was put down, from a place far from it": (
        put_down_then('<ActorMovement target="table_front"/>'),
        "part in area 'table' (NextObject at ",
        "), put down by ActorPlace at ",
        "at (1.90, 0.95, 0.98) is 1.96 m from where the person stands (location 'table_front'",
        'name="again"',
    ),
    "a pick off its own branch's area, from a place far from it": (
        either_table("table_front"),
        "in area 'other' (NextObject at ",
        "at (2.20, 0.60, 0.93) is 2.36 m from where the person stands (location 'table_front'",
        'name="other"',
    ),
}


@pytest.mark.parametrize("name", TOO_FAR)
def test_a_pick_really_out_of_reach_is_still_found(name, tmp_path, hrc_drake):
    tree, *says, at = TOO_FAR[name]
    bad = case(tree, tuple(says), at)
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, bad))
    assert_one_line_error(status, err, expected_place(tmp_path, bad), *says)


def test_each_thing_a_fallback_may_have_written_is_judged(tmp_path, hrc_drake):
    """A user's pattern (#26): take a part found on the table, or else one made at a pose
    of its own. Validate said nothing of a pick whose object a Fallback chose; the made
    part lies 2.5 m from where the person stands, and the line names the SpawnObject."""
    tree = (
        '<ActorMovement target="table_front"/>\n'
        "      <Fallback>\n"
        '        <NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>\n'
        '        <SpawnObject type="part" pose="2.4;0.8;0.93" object_id="{p}"/>\n'
        "      </Fallback>\n"
        '      <ActorPick object_id="{p}"/>'
    )
    says = (
        "port 'object_id': part made at '2.4;0.8;0.93' (SpawnObject at ",
        "at (2.40, 0.80, 0.93) is 2.49 m from where the person stands (location 'table_front'",
    )
    bad = case(tree, says)
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, bad))
    assert_one_line_error(status, err, expected_place(tmp_path, bad), *says)


def test_a_put_down_after_a_fallback_that_found_the_object_is_judged(tmp_path, hrc_drake):
    """A user's flow-rack cell (#26): the box found and walked to in a Fallback's first
    try (else it waits), then taken and put where an arm goes into the rack. Validate
    said nothing, the run refused the put-down; the try that found it is judged (here a
    tote put down past the board's back edge, which only the tote's size tells)."""
    base = CASES["a put-down past a shelf board's back edge of the tote carried there"]
    find = '<NextObject area="table" filter="type=tote" object_id="{t}" pose="{at}"/>'
    walk = '<ActorMovement target="table_front"/>'
    tree = base.files[base.found_in]
    assert find + walk in tree
    tried = f"<Fallback><Sequence>{find}{walk}</Sequence><AlwaysSuccess/></Fallback>"
    says = (*(t.replace("): ", " gave: ") for t in base.says), "), holding what NextObject at ")
    bad = dataclasses.replace(
        base, says=says, files={**base.files, base.found_in: tree.replace(find + walk, tried)}
    )
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, bad))
    assert_one_line_error(status, err, expected_place(tmp_path, bad), *bad.says)


def fallback_then_other(first_walk: str):
    """A Fallback: the part off the table, carried to the other table (walking to
    `first_walk` first), or else the part off the other table, taken where the person
    stands then."""
    return (
        "<Fallback>\n"
        f"      <Sequence>{first_walk}\n"
        '      <NextObject area="table" filter="type=part" object_id="{p}" pose="{at}"/>\n'
        '      <ActorPick object_id="{p}"/><ActorCarry target="other_front"/>\n'
        '      <ActorPlace target="1.9;0.95;0.98"/></Sequence>\n'
        '      <Sequence><NextObject area="other" filter="type=part" object_id="{p}"/>\n'
        '      <ActorPick name="other" object_id="{p}"/></Sequence>\n'
        "      </Fallback>"
    )


SECOND_TRIES = {
    "from where the person stood before the Fallback": (
        '<ActorMovement target="table_front"/>\n      ' + fallback_then_other("")
    ),
    "from where the first try walked before it found nothing": (
        '<ActorMovement target="other_front"/>\n      '
        + fallback_then_other('<ActorMovement target="table_front"/>')
    ),
}


@pytest.mark.parametrize("name", SECOND_TRIES)
def test_a_pick_in_a_fallbacks_second_try_is_judged(name, tmp_path, hrc_drake):
    """A user's assembly cell (#26): `Fallback { LoadLarge; LoadSmall }` at a rack, whose
    second try runs once the first's NextObject finds no large housing. Validate said
    nothing of the second try's pick (the first try walks, so where the person stood was
    "not known"), and found it unreachable with the two tries swapped; the run meets it
    with the first try failed at its NextObject, having run what came before that."""
    says = (
        "port 'object_id': part in area 'other' (NextObject at ",
        "at (2.20, 0.60, 0.93) is 2.36 m from where the person stands (location 'table_front'",
    )
    bad = case(SECOND_TRIES[name], says, 'name="other"')
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, bad))
    assert_one_line_error(status, err, expected_place(tmp_path, bad), *says)


BIG = (
    "safety:\n",
    "    big: {shape: box, size: [0.1, 0.1, 0.12], mass: 0.5, capacity: 4}\n"
    f"{OBJECTS}{PART_ON_TABLE}    - {{type: big, pose: {{translation: [-0.3, 0.6, 0.96]}}}}\n"
    "safety:\n",
)
"""A part (6 cm high) and a big part (12 cm high) on the table."""


def test_a_put_down_in_a_switch_on_the_type_is_judged_with_that_type(tmp_path, hrc_drake):
    """A user's assembly cell (#26): a housing of either type found, its type read and
    switched on, each branch putting down its own type at its own height. Validate judged
    the branch for small parts holding a big one too: "3.0 cm into 'work_table'"; with the
    cases swapped, the big part is put down there and still found."""
    tree = (
        '<ActorMovement target="table_front"/>\n'
        "      <Fallback>\n"
        '        <NextObject area="table" filter="type=part" object_id="{p}"/>\n'
        '        <NextObject area="table" filter="type=big" object_id="{p}"/>\n'
        "      </Fallback>\n"
        '      <ObjectAttribute object_id="{p}" attribute="type" value="{kind}"/>\n'
        '      <ActorPick object_id="{p}"/>\n'
        '      <Switch2 variable="{kind}" case_1="big" case_2="part">\n'
        '        <ActorPlace target="0.2;0.6;0.96"/>\n'
        '        <ActorPlace target="0.2;0.6;0.93"/>\n'
        "        <AlwaysFailure/>\n"
        "      </Switch2>"
    )
    fine = person('<ActorMovement target="door"/>', tree, (), None, changes=[FRONTS, BIG])
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, fine))
    assert status == 0, err
    swapped = tree.replace('case_1="big" case_2="part"', 'case_1="part" case_2="big"')
    says = ("holding what NextObject at ", "would be 3.0 cm into 'work_table' where it is put")
    bad = person('<ActorMovement target="door"/>', swapped, says, "0.93", changes=[FRONTS, BIG])
    status, _, err = hrc_drake("validate", write_workspace(tmp_path, bad))
    assert_one_line_error(status, err, expected_place(tmp_path, bad), *says)
