"""Measures the ergonomic picture of every bundled scenario with a person and writes it
into the README's scenario table (between its `ergonomics` markers): who lifts what, the
worst RULA and REBA scores and the largest NIOSH lifting index of one run each.

    .venv/bin/python docs/scenario_ergonomics.py [--duration S] [--check]

Each scenario runs with its own seed and duration (or `--duration`); `--check` prints the
table without writing the README.
"""

import argparse
import re
from collections import Counter
from pathlib import Path

from hrc_drake import load_scenario, run
from hrc_drake.scenario import bundled_scenarios

README = Path(__file__).resolve().parents[1] / "README.md"
BEGIN, END = "<!-- ergonomics:begin -->", "<!-- ergonomics:end -->"
HEADER = (
    "| scenario | run | the person lifts | worst RULA | worst REBA | largest lifting index |\n"
    "|---|---|---|---|---|---|"
)


def lifted(lifts: list[dict]) -> str:
    """`3 x box (7 kg, both hands)`, per object type, mass and hands."""
    kinds = Counter(
        (lift["object"].rsplit(" ", 1)[0], lift["mass"], lift["hands"]) for lift in lifts
    )
    if not kinds:
        return "nothing"
    hands = {"both_hands": "both hands", "right_hand": "right hand", "left_hand": "left hand"}
    return ", ".join(
        f"{n} x {kind} ({mass:g} kg, {hands.get(holder, holder)})"
        for (kind, mass, holder), n in sorted(kinds.items())
    )


def worst(values: dict) -> str:
    doing = values["activity"] or "standing"
    return f"{values['score']} ({values['side']}, {doing}, {values['time']:g} s)"


def largest(lift: dict) -> str:
    if not lift:
        return "-"
    value = "out of range" if lift["value"] is None else f"{lift['value']:.2f}"
    return f"{value} ({lift['object']}, {lift['end']})"


def row(name: str, metrics: dict) -> str:
    e = metrics["ergonomics"]
    person = e["person"]
    size = f"{person['height']:g} m {person['mass']:g} kg"
    run_ = f"seed {metrics['seed']}, {metrics['duration']:g} s, {size}"
    cells = [name, run_, lifted(e["lifts"]), worst(e["rula"]["max"]), worst(e["reba"]["max"])]
    return "| " + " | ".join([*cells, largest(e["lifting_index_max"])]) + " |"


def table(duration: float | None) -> str:
    rows = []
    for name in bundled_scenarios():
        scenario = load_scenario(name, [("visualization.record", False)])
        if scenario.human is None:
            continue
        rows.append(row(name, run(scenario, duration=duration).metrics))
    return "\n".join([HEADER, *rows])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=None)
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    text = table(args.duration)
    if args.check:
        print(text)
        return
    readme = README.read_text()
    pattern = re.compile(f"{re.escape(BEGIN)}.*?{re.escape(END)}", re.S)
    README.write_text(pattern.sub(f"{BEGIN}\n{text}\n{END}", readme))


if __name__ == "__main__":
    main()
