"""Bad command lines: one line naming the option (and the field for `--set`), exit status
2, nothing written; values from the command line meet the same checks as the file's."""

import pytest

from tests.corpus.corpus_helpers import assert_one_line_error, write_workspace

# (arguments, what the line says); {s} is the good scenario, {tmp} a scratch directory,
# {file} an existing file, {run} a directory holding a finished run.
CASES = {
    "no command": ((), ("the following arguments are required: COMMAND",)),
    "unknown command": (("rnu",), ("invalid choice: 'rnu'",)),
    "unknown option": (("run", "{s}", "--sed", "1"), ("unrecognized arguments: --sed",)),
    "missing scenario": (("run",), ("run: the following arguments are required: scenario",)),
    "unknown scenario": (("run", "bsae"), ("bsae: no such scenario", "did you mean 'base'?")),
    "seed negative": (("run", "{s}", "--seed", "-1"), ("--seed -1: must lie within 0..",)),
    "seed not a number": (
        ("run", "{s}", "--seed", "x"),
        ("run: argument --seed: invalid int value: 'x'",),
    ),
    "seed too large": (
        ("run", "{s}", "--seed", "99999999999999999999999"),
        ("--seed 99999999999999999999999: must lie within",),
    ),
    "duration inf": (
        ("run", "{s}", "--duration", "inf"),
        ("--duration inf: must be a finite number",),
    ),
    "duration nan": (
        ("run", "{s}", "--duration", "nan"),
        ("--duration nan: must be a finite number",),
    ),
    "duration negative": (
        ("run", "{s}", "--duration", "-1"),
        ("--duration -1.0: must be positive",),
    ),
    "duration zero": (("run", "{s}", "--duration", "0"), ("--duration 0.0: must be positive",)),
    "duration text": (
        ("run", "{s}", "--duration", "long"),
        ("run: argument --duration: invalid float value: 'long'",),
    ),
    "set time_step zero": (
        ("run", "{s}", "--set", "plant.time_step=0"),
        ("--set plant.time_step=0.0: must lie within",),
    ),
    "set time_step inf": (
        ("run", "{s}", "--set", "plant.time_step=.inf"),
        ("--set plant.time_step=inf: must be a finite number",),
    ),
    "set duration negative": (
        ("run", "{s}", "--set", "duration=-1"),
        ("--set duration=-1.0: must be positive",),
    ),
    "set unknown variant": (
        ("run", "{s}", "--set", "robot.variant=lbr_iisy3_r770"),
        (
            "--set robot.variant=lbr_iisy3_r770: unknown robot variant",
            "did you mean 'lbr_iisy3_r760'?",
        ),
    ),
    "set unknown tool": (
        ("run", "{s}", "--set", "robot.tool=hammer"),
        ("--set robot.tool=hammer: unknown tool 'hammer'",),
    ),
    "set unknown field": (
        ("run", "{s}", "--set", "durration=1"),
        ("--set durration: unknown field 'durration' (did you mean 'duration'?)",),
    ),
    "set unknown nested field": (
        ("run", "{s}", "--set", "safety.vh=1"),
        ("--set safety.vh: unknown field 'vh' (did you mean 'v_h'?)",),
    ),
    "set wrong type": (
        ("run", "{s}", "--set", "duration=fast"),
        ("--set duration: 'fast' is not a float",),
    ),
    "set without value": (
        ("run", "{s}", "--set", "duration"),
        ("--set duration: expected PATH=VALUE",),
    ),
    "set a section": (
        ("run", "{s}", "--set", "cell=1"),
        ("--set cell: only number, boolean and text fields can be set",),
    ),
    "set an item of a list": (
        ("run", "{s}", "--set", "workpieces.objects.0.pose=1"),
        (
            "--set workpieces.objects.0.pose: 'workpieces.objects' is a list: --set reaches "
            "fields and mapping entries, not a list's items (change it in the scenario file)",
        ),
    ),
    "set a vector": (
        ("run", "{s}", "--set", "locations.door.translation=1"),
        ("(a list: change it in the scenario file)",),
    ),
    "set a number in scientific notation": (
        ("run", "{s}", "--set", "duration=-1e3"),
        ("--set duration=-1000.0: must be positive",),
    ),
    "set text for a number": (
        ("run", "{s}", "--set", "duration=1e3x"),
        ("--set duration: '1e3x' is not a float",),
    ),
    "set a grid in run": (
        ("run", "{s}", "--set", "duration=1,2"),
        ("run: --set takes one value per field",),
    ),
    "set v_h negative": (
        ("run", "{s}", "--set", "safety.v_h=-1"),
        ("--set safety.v_h=-1.0: must not be negative",),
    ),
    "set min_scale too large": (
        ("run", "{s}", "--set", "safety.min_scale=2"),
        ("--set safety.min_scale=2.0: must lie within 0..1",),
    ),
    "set person too tall": (
        ("run", "{s}", "--set", "human.height=2.5"),
        ("--set human.height=2.5: must lie within",),
    ),
    "set the planner's seed (it derives from the run's)": (
        ("run", "{s}", "--set", "robot.motion.seed=3"),
        ("--set robot.motion.seed: unknown field 'seed'",),
    ),
    "set bool as number": (
        ("run", "{s}", "--set", "safety.ssm=3"),
        ("--set safety.ssm: '3' is not a bool",),
    ),
    "out is a file": (("run", "{s}", "--out", "{file}"), ("{file}: is a file, not a directory",)),
    "out holds a run": (
        ("run", "{s}", "--out", "{run}"),
        ("{run}: the run directory is not empty",),
    ),
    "out cannot be created": (
        ("run", "{s}", "--out", "/sys/hrc_drake/run"),
        ("/sys/hrc_drake/run: cannot create the run directory",),
    ),
    "out under a file": (
        ("run", "{s}", "--out", "{file}/run"),
        ("{file}/run: cannot create the run directory",),
    ),
    "diagram to a text file": (
        ("diagram", "{s}", "-o", "{tmp}/d.txt"),
        ("-o {tmp}/d.txt: use a .svg, .png, .dot file name",),
    ),
    "diagram into a directory": (
        ("diagram", "{s}", "-o", "{tmp}/d.svg"),
        ("-o {tmp}/d.svg: is a directory",),
    ),
    "diagram into a missing directory": (
        ("diagram", "{s}", "-o", "{tmp}/no/d.svg"),
        ("-o {tmp}/no/d.svg: directory '{tmp}/no' does not exist",),
    ),
    "diagram without -o": (
        ("diagram", "{s}"),
        ("diagram: the following arguments are required: -o/--output",),
    ),
    "tree to a pdf": (
        ("tree", "{s}", "--agent", "robot", "-o", "{tmp}/t.pdf"),
        ("-o {tmp}/t.pdf: use a .svg, .png, .dot file name",),
    ),
    "tree without agent": (("tree", "{s}", "-o", "{tmp}/t.svg"), ("give --agent, one of: robot",)),
    "tree of an agent without one": (
        ("tree", "{s}", "--agent", "human", "-o", "{tmp}/t.svg"),
        ("give --agent, one of: robot",),
    ),
    "tree of an unknown agent": (
        ("tree", "{s}", "--agent", "cat", "-o", "{tmp}/t.svg"),
        ("argument --agent: invalid choice: 'cat'",),
    ),
    "tree id unknown": (
        ("tree", "{tmp}/robot.xml", "--tree-id", "Robto", "-o", "{tmp}/t.svg"),
        ("{tmp}/robot.xml:1: tree 'Robto': no BehaviorTree with ID 'Robto'",),
    ),
    "tree file missing": (
        ("tree", "{tmp}/nothing.xml", "-o", "{tmp}/t.svg"),
        ("{tmp}/nothing.xml: cannot read the tree file",),
    ),
    "list xml without nodes": (("list", "--xml", "{tmp}/n.xml"), ("--xml goes with --nodes",)),
    "list xml into a directory": (
        ("list", "--nodes", "--xml", "{tmp}"),
        ("--xml {tmp}: is a directory",),
    ),
    "list xml into a missing directory": (
        ("list", "--nodes", "--xml", "{tmp}/no/n.xml"),
        ("directory '{tmp}/no' does not exist",),
    ),
    "sweep seeds not numbers": (
        ("sweep", "{s}", "--seeds", "a:b"),
        ("--seeds a:b: expected START:STOP, N or a comma list",),
    ),
    "sweep seeds empty range": (
        ("sweep", "{s}", "--seeds", "5:5"),
        ("--seeds 5:5: no seeds in that range",),
    ),
    "sweep seeds negative": (
        ("sweep", "{s}", "--seeds=-3:2"),
        ("--seeds -3:2: seeds lie within 0..",),
    ),
    "sweep zero workers": (
        ("sweep", "{s}", "--workers", "0"),
        ("sweep: argument --workers: must lie within 1..",),
    ),
    "sweep too many workers": (
        ("sweep", "{s}", "--workers", "100000"),
        ("sweep: argument --workers: must lie within 1..", "got 100000"),
    ),
    "sweep workers not a number": (
        ("sweep", "{s}", "--workers", "two"),
        ("sweep: argument --workers: 'two' is not a whole number",),
    ),
    "sweep seeds with an empty part": (
        ("sweep", "{s}", "--seeds", "1,,2"),
        ("--seeds 1,,2: expected START:STOP, N or a comma list",),
    ),
    "sweep seeds beyond the largest": (
        ("sweep", "{s}", "--seeds", "0:99999999999999999999999"),
        ("--seeds 0:99999999999999999999999: seeds lie within 0..",),
    ),
    "sweep sets the seed": (
        ("sweep", "{s}", "--set", "seed=1"),
        ("--set seed: use --seeds to choose seeds",),
    ),
    "sweep grid value out of range": (
        ("sweep", "{s}", "--set", "duration=1,-1"),
        ("--set duration=-1.0: must be positive",),
    ),
    "sweep grid of unknown variants": (
        ("sweep", "{s}", "--set", "robot.variant=lbr_iisy3_r760,robot"),
        ("--set robot.variant=robot: unknown robot variant",),
    ),
    "sweep dask address malformed": (
        ("sweep", "{s}", "--dask", "tcp://a b", "--out", "{tmp}/sweep"),
        ("--dask tcp://a b: expected a scheduler address like tcp://HOST:PORT",),
    ),
    "sweep dask address without port": (
        ("sweep", "{s}", "--dask", "localhost", "--out", "{tmp}/sweep"),
        ("--dask localhost: expected a scheduler address",),
    ),
    "sweep out is a file": (
        ("sweep", "{s}", "--out", "{file}"),
        ("{file}: is a file, not a directory",),
    ),
    "sweep out holds a run": (
        ("sweep", "{s}", "--out", "{run}"),
        ("{run}: holds other files but no runs.jsonl",),
    ),
    "set a section the scenario lacks": (
        ("run", "base", "--set", "human.height=1.8"),
        ("--set human.height: the scenario has no 'human' section to change",),
    ),
    "set an entry the mapping lacks": (
        ("run", "{s}", "--set", "parameters.sped=1"),
        ("--set parameters.sped: 'parameters' has no entry 'sped' (did you mean 'speed'?)",),
    ),
    "set a port of no node": (
        ("run", "{s}", "--set", "trees.robot.ports.Ofset.offset=0;0;1"),
        ("--set trees.robot.ports.Ofset.offset=0;0;1: no node named 'Ofset' in the robot's",),
    ),
    "set a port value the port cannot read": (
        ("run", "{s}", "--set", "trees.robot.ports.OffsetPose.offset=0;0"),
        ("--set trees.robot.ports.OffsetPose.offset=0;0: cannot convert '0;0' to Pose",),
    ),
    "falsify without a falsify section": (
        ("falsify", "{s}", "--budget", "2", "--out", "{tmp}/search"),
        ("{s}: no 'falsify:' section",),
    ),
    "falsify without a budget": (
        ("falsify", "walk_up"),
        ("falsify: the following arguments are required: --budget",),
    ),
    "falsify budget zero": (
        ("falsify", "walk_up", "--budget", "0"),
        ("falsify: argument --budget: must be at least 1, got 0",),
    ),
    "falsify with a grid": (
        ("falsify", "walk_up", "--budget", "2", "--set", "duration=1,2"),
        ("falsify: --set takes one value per field",),
    ),
    "falsify batch zero": (
        ("falsify", "walk_up", "--budget", "2", "--set", "falsify.batch=0", "--out", "{tmp}/s"),
        ("--set falsify.batch=0: must be positive, got 0",),
    ),
    "falsify duration negative": (
        ("falsify", "walk_up", "--budget", "2", "--duration", "-3", "--out", "{tmp}/s"),
        ("--duration -3.0: must be positive",),
    ),
    "falsify dask address malformed": (
        ("falsify", "walk_up", "--budget", "2", "--dask", "tcp://a b", "--out", "{tmp}/s"),
        ("--dask tcp://a b: expected a scheduler address like tcp://HOST:PORT",),
    ),
    "falsify out holds a run": (
        ("falsify", "walk_up", "--budget", "2", "--out", "{run}"),
        ("{run}: holds other files but no runs.jsonl",),
    ),
    "validate without scenario": (
        ("validate",),
        ("validate: the following arguments are required: scenario",),
    ),
}


@pytest.fixture
def places(tmp_path):
    scenario = write_workspace(tmp_path)
    (tmp_path / "d.svg").mkdir()
    (tmp_path / "file.txt").write_text("not a directory\n")
    (tmp_path / "run").mkdir()
    (tmp_path / "run" / "report.json").write_text("{}\n")
    return {"s": scenario, "tmp": tmp_path, "file": tmp_path / "file.txt", "run": tmp_path / "run"}


@pytest.mark.parametrize("name", CASES)
def test_bad_command_line_is_one_line(name, places, hrc_drake):
    arguments, says = CASES[name]
    before = sorted(places["tmp"].rglob("*"))
    status, out, err = hrc_drake(*(a.format(**places) for a in arguments))
    assert_one_line_error(status, err, *(s.format(**places) for s in says))
    assert sorted(places["tmp"].rglob("*")) == before, "a refused command wrote files"
    assert out == ""


def test_dask_with_nothing_listening_fails_fast_and_writes_nothing(places, hrc_drake):
    """A port nobody listens on: one line within the connect timeout, no empty rows."""
    out = places["tmp"] / "sweep"
    status, _, err = hrc_drake("sweep", places["s"], "--dask", "tcp://127.0.0.1:9", "--out", out)
    assert_one_line_error(status, err, "--dask tcp://127.0.0.1:9: no Dask scheduler answered")
    assert not out.exists()


def test_default_run_directory_is_never_mixed_with_an_earlier_run(places, hrc_drake, monkeypatch):
    """Without --out, a second run of the same scenario and seed goes to a fresh -2."""
    monkeypatch.chdir(places["tmp"])
    first = places["tmp"] / "runs" / "corpus-seed0"
    first.mkdir(parents=True)
    (first / "bt_robot.btlog").write_bytes(b"an earlier run")
    status, out, err = hrc_drake("run", places["s"], "--duration", "0.05")
    assert status == 0, err
    assert "runs/corpus-seed0-2/report.json" in out
    assert sorted(p.name for p in first.iterdir()) == ["bt_robot.btlog"]
    assert (places["tmp"] / "runs" / "corpus-seed0-2" / "bt_robot.btlog").is_file()
