"""`hrc-drake layout`: the cell from above as the robot and the person can use it (the
robot's reach at its targets' heights, where the person walks and stands, the places,
areas and objects, validate's findings marked), without simulating."""

from pathlib import Path

from hrc_drake.cli.arguments import check_output


def add_commands(commands) -> None:
    layout = commands.add_parser(
        "layout", help="draw the cell from above as the robot and the person can use it"
    )
    layout.add_argument("scenario")
    layout.add_argument("-o", "--output", type=Path, required=True, help=".png or .svg")
    layout.set_defaults(command=_layout)


def _layout(args) -> int:
    from hrc_drake.layout import layout_of, write_layout
    from hrc_drake.scenario import load_scenario, resolve_scenario_path

    check_output(args.output, "-o", (".png", ".svg"))
    scenario = load_scenario(args.scenario)
    layout = layout_of(scenario, resolve_scenario_path(args.scenario))
    write_layout(layout, args.output)
    print(args.output)
    if layout.findings:
        print(f"{len(layout.findings)} findings marked (hrc-drake validate lists them)")
    return 0
