"""`hrc-drake diagram`, `validate`, `tree`, `list` and `clip`: the commands that look at a
scenario, its trees and clips without simulating."""

import sys
from pathlib import Path

from hrc_drake.cli.arguments import EXIT_USAGE, PROG, add_set_option, check_output, single_sets
from hrc_drake.wiring import AGENTS
from hrc_drake.yaml_check import InputError


def add_commands(commands, parser_class) -> None:
    diagram = commands.add_parser("diagram", help="export the scenario's system diagram")
    diagram.add_argument("scenario")
    diagram.add_argument("-o", "--output", type=Path, required=True, help=".svg, .png or .dot")
    diagram.set_defaults(command=_diagram)

    validate = commands.add_parser("validate", help="check a scenario without simulating")
    validate.add_argument("scenario")
    add_set_option(validate)
    validate.set_defaults(command=_validate, seed=None, duration=None)

    tree = commands.add_parser("tree", help="render a behavior tree to .svg, .png or .dot")
    tree.add_argument("source", help="a tree XML file, or a scenario (then give --agent)")
    tree.add_argument("--agent", choices=AGENTS, help="whose tree in the scenario")
    tree.add_argument("--tree-id", help="which tree of the file (default: its main tree)")
    tree.add_argument("-o", "--output", type=Path, required=True, help=".svg, .png or .dot")
    tree.set_defaults(command=_tree)

    listing = commands.add_parser(
        "list", help="bundled scenarios and robot variants, or the behavior tree nodes"
    )
    listing.add_argument(
        "--nodes", action="store_true", help="every tree node with its ports (the palette)"
    )
    listing.add_argument(
        "--xml",
        nargs="?",
        const="-",
        metavar="FILE",
        help="with --nodes: write Groot2's TreeNodesModel XML (to FILE, default stdout)",
    )
    listing.set_defaults(command=_list)
    _add_clip_commands(commands, parser_class)


def _add_clip_commands(commands, parser_class) -> None:
    clip = commands.add_parser(
        "clip", help="the person's motion clips: list them, export to BVH, import from BVH"
    )
    actions = clip.add_subparsers(required=True, metavar="ACTION", parser_class=parser_class)
    listing = actions.add_parser("list", help="the built-in clips (and a scenario's own)")
    listing.add_argument("scenario", nargs="?", help="also list this scenario's human.clips")
    listing.set_defaults(command=_clip_list)
    export = actions.add_parser("export", help="write a clip as BVH (our skeleton, cm, Y up)")
    export.add_argument("name", help="a clip name (see `clip list`)")
    export.add_argument("-o", "--output", type=Path, required=True, help="a .bvh file")
    export.add_argument("--scenario", help="also look among this scenario's human.clips")
    export.set_defaults(command=_clip_export)
    imported = actions.add_parser(
        "import", help="map a BVH take (Mixamo/CMU bone names) onto the person, as clip JSON"
    )
    imported.add_argument("bvh", type=Path, help="a .bvh file")
    imported.add_argument(
        "-o", "--output", type=Path, help="clip .json to write (default: NAME.json here)"
    )
    imported.add_argument("--name", help="the clip's name (default: the file's name)")
    imported.add_argument("--loop", action="store_true", help="the take loops")
    imported.set_defaults(command=_clip_import)


def _diagram(args) -> int:
    from hrc_drake.builder import build_diagram
    from hrc_drake.diagram_export import write_diagram
    from hrc_drake.scenario import load_scenario

    check_output(args.output, "-o", (".svg", ".png", ".dot"))
    write_diagram(build_diagram(load_scenario(args.scenario)), args.output)
    print(args.output)
    return 0


def _validate(args) -> int:
    """The scenario loads (its first mistake is one line; the safety sensors' mistakes are
    findings, all at once), then every finding that needs no simulation, one line each;
    exit status 2 when there is any. `--set` checks the scenario as a run with the same
    `--set` would have it (a person of another size: #26)."""
    from hrc_drake.scenario import load_scenario, resolve_scenario_path
    from hrc_drake.scenario.findings import findings

    overrides, _ = single_sets(args, "validate", "validate one value at a time")
    scenario = load_scenario(args.scenario, overrides, sensors=False)
    found = findings(scenario, resolve_scenario_path(args.scenario))
    person = scenario.human.survey_person() if scenario.human is not None else ""
    if person:
        print(f"{args.scenario}: person: {person}")
    for finding in found:
        print(f"{PROG}: error: {finding}", file=sys.stderr)
    if found:
        return EXIT_USAGE
    trees = ", ".join(f"{agent}: {Path(tree.file).name}" for agent, tree in scenario.trees.items())
    print(f"{args.scenario}: ok ({scenario.name}{'; trees ' + trees if trees else ''})")
    return 0


def _tree(args) -> int:
    from hrc_drake.bt import BTError, load_tree, render_tree
    from hrc_drake.nodes import hrc_registry
    from hrc_drake.scenario import load_scenario

    check_output(args.output, "-o", (".svg", ".png", ".dot"))
    if args.source.endswith(".xml"):
        try:
            tree = load_tree(Path(args.source), hrc_registry(), tree_id=args.tree_id)
        except BTError as error:
            raise InputError(str(error)) from None
    else:
        scenario = load_scenario(args.source)
        if args.agent not in scenario.trees:
            known = ", ".join(scenario.trees) or "none"
            raise InputError(f"{args.source}: give --agent, one of: {known}")
        tree, _ = scenario.agent_tree(args.agent)
    render_tree(tree, args.output)
    print(args.output)
    return 0


def _list(args) -> int:
    if args.nodes:
        return _list_nodes(args.xml)
    if args.xml:
        raise InputError("--xml goes with --nodes")
    from hrc_drake.iisy import VARIANTS
    from hrc_drake.scenario import bundled_scenarios, load_scenario

    print("scenarios:")
    for name in bundled_scenarios():
        print(f"  {name:16s} {load_scenario(name).description}")
    print("robot variants:")
    for name, variant in VARIANTS.items():
        print(
            f"  {name:16s} payload {variant.payload:g} kg, reach {variant.reach:g} m, "
            f"{variant.total_mass:g} kg"
        )
    _list_shared_subtrees()
    return 0


def _list_shared_subtrees() -> None:
    """The bundled trees' shared SubTrees, by file: a cell of a user's own copies the file
    into a folder beside its trees and includes it (a user's cell included them by the
    absolute path of a checkout; `common/robot.xml` beside a cell's own `robot.xml` would
    take its name)."""
    from xml.etree import ElementTree

    from hrc_drake.paths import resource_dir

    common = resource_dir("trees") / "common"
    print(
        f"shared SubTrees (in {common}; copy a file into a folder common/ beside your trees "
        'and <include path="common/FILE"/> it):'
    )
    for path in sorted(common.glob("*.xml")):
        ids = [tree.get("ID") for tree in ElementTree.parse(path).getroot().iter("BehaviorTree")]
        print(f"  {path.name:18s} {', '.join(ids)}")


def _list_nodes(xml_file: str | None) -> int:
    from hrc_drake.bt import tree_nodes_model_xml
    from hrc_drake.nodes import hrc_registry, palette_text

    registry = hrc_registry()
    if xml_file is None:
        print(palette_text(registry))
    elif xml_file == "-":
        print(tree_nodes_model_xml(registry))
    else:
        check_output(Path(xml_file), "--xml", ())
        Path(xml_file).write_text(tree_nodes_model_xml(registry) + "\n")
        print(xml_file)
    return 0


def _scenario_clips(scenario: str | None) -> dict:
    from hrc_drake.human.clip_files import clip_catalog
    from hrc_drake.scenario import load_scenario

    human = load_scenario(scenario).human if scenario else None
    return clip_catalog(human.clips if human is not None else ())


def _clip_list(args) -> int:
    from hrc_drake.human.clip_files import describe

    for name, clip in sorted(_scenario_clips(args.scenario).items()):
        print(f"  {name:12s} {describe(clip)}")
    return 0


def _clip_export(args) -> int:
    from hrc_drake.human.bvh import export_bvh

    check_output(args.output, "-o", (".bvh",))
    clips = _scenario_clips(args.scenario)
    if args.name not in clips:
        raise InputError(f"clip export: no clip '{args.name}' (known: {', '.join(sorted(clips))})")
    export_bvh(clips[args.name], args.output)
    print(args.output)
    return 0


def _clip_import(args) -> int:
    from hrc_drake.human.clip import clip_to_json
    from hrc_drake.human.clip_files import describe, read_clip_file

    if args.bvh.suffix.lower() != ".bvh":
        raise InputError(f"{args.bvh}: use a .bvh file")
    output = args.output or Path(f"{args.name or args.bvh.stem}.json")
    check_output(output, "-o", (".json",))
    clip = read_clip_file(args.bvh, name=args.name, loop=args.loop)
    output.write_text(clip_to_json(clip))
    print(f"{output}: {clip.name}, {describe(clip)}")
    return 0
