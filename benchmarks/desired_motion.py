"""What handing the controller its desired motion costs per plant step, in C++: the
station's systems (`add_step_samples`: a step clock, a one-hot vector of the step's slot,
times RobotMotion's samples) against the SymbolicVectorSystem that evaluated RobotMotion's
quintic segment at every step before (kept here as the reference), and against nothing.

Three diagrams advance in turns, timed by this process's CPU time: each reads its desired
state into a ZeroOrderHold at every plant step, as the controller does; `none` reads a
constant (the cost of the step itself). Prints µs per plant step, and each chain's cost
net of `none` against the bare robot's whole cost per step (the bare plant and controller
of `benchmarks/scenarios.py`, holding still).

    .venv/bin/python benchmarks/desired_motion.py [--duration 20] [--step 0.002]
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from pydrake.symbolic import MakeVectorVariable, Variable
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.primitives import (
    ConstantVectorSource,
    MatrixGain,
    SymbolicVectorSystem,
    ZeroOrderHold,
)

from hrc_drake.iisy import VARIANTS
from hrc_drake.motion.execution import SEGMENT_COEFFICIENTS
from hrc_drake.motion.options import MotionOptions
from hrc_drake.scenario import load_scenario, overridden
from hrc_drake.seeding import stream
from hrc_drake.station import StationSpec
from hrc_drake.systems.robot_motion import RobotMotion, add_step_samples, desired_differences

sys.path.insert(0, str(Path(__file__).resolve().parent))
from base_scenario import bare_diagram  # noqa: E402

from scenarios import timed_in_turns  # noqa: E402

VARIANT = "lbr_iisy3_r760"
JOINTS = len(VARIANTS[VARIANT].joint_names)


def symbolic_samples(time_step: float) -> SymbolicVectorSystem:
    """The former desired-motion system: q(t - h), q(t), q(t + h) of the segment input
    (its start, then each joint's quintic) in Horner form."""
    t = Variable("t")
    segment = MakeVectorVariable(1 + JOINTS * SEGMENT_COEFFICIENTS, "segment")
    rows = np.array(segment[1:]).reshape(JOINTS, SEGMENT_COEFFICIENTS).tolist()
    samples = []
    for k in (-1, 0, 1):
        since = t - segment[0] + k * time_step
        for row in rows:
            value = row[-1]
            for c in reversed(row[:-1]):
                value = c + since * value
            samples.append(value)
    return SymbolicVectorSystem(time=t, input=segment, output=samples)


def held(builder, output, time_step: float) -> None:
    """`output` read at every plant step, as the controller reads its desired state."""
    hold = builder.AddSystem(ZeroOrderHold(time_step, output.size()))
    builder.Connect(output, hold.get_input_port())


def none_diagram(time_step: float):
    builder = DiagramBuilder()
    source = builder.AddSystem(ConstantVectorSource(np.zeros(3 * JOINTS)))
    held(builder, source.get_output_port(), time_step)
    return builder.Build()


def symbolic_diagram(time_step: float):
    builder = DiagramBuilder()
    segment = np.concatenate([[0.0], np.random.default_rng(0).normal(size=6 * JOINTS)])
    source = builder.AddSystem(ConstantVectorSource(segment))
    samples = builder.AddSystem(symbolic_samples(time_step))
    builder.Connect(source.get_output_port(), samples.get_input_port())
    differences = builder.AddSystem(MatrixGain(desired_differences(JOINTS, time_step)))
    builder.Connect(samples.get_output_port(), differences.get_input_port())
    held(builder, differences.get_output_port(), time_step)
    return builder.Build()


def station_diagram(time_step: float):
    """The station's systems, reading RobotMotion's initial samples (held constant: no
    RobotMotion update runs)."""
    motion = RobotMotion(
        StationSpec(VARIANT), stream(0, "benchmark"), MotionOptions(), sample_step=time_step
    )
    samples = motion.GetOutputPort("desired_samples").Eval(motion.CreateDefaultContext())
    builder = DiagramBuilder()
    source = builder.AddSystem(ConstantVectorSource(samples))
    split = add_step_samples(builder, source.get_output_port(), motion.sample_slots, time_step)
    held(builder, split.get_output_port(0), time_step)
    return builder.Build()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=20.0)
    parser.add_argument("--step", type=float, default=0.002)
    args = parser.parse_args()
    scenario = overridden(load_scenario("coexistence"), [("plant.time_step", args.step)])
    diagrams = {
        "none": none_diagram(args.step),
        "symbolic (before)": symbolic_diagram(args.step),
        "station": station_diagram(args.step),
        "bare robot": bare_diagram(scenario),
    }
    simulators = []
    for diagram in diagrams.values():
        simulators.append(Simulator(diagram))
        simulators[-1].Initialize()
    times = timed_in_turns(simulators, args.duration, time.process_time)
    per_step = {
        name: 1e6 * t * args.step / args.duration for name, t in zip(diagrams, times, strict=True)
    }
    for name, micros in per_step.items():
        line = f"{name:18s} {micros:7.2f} µs per step"
        if name in ("symbolic (before)", "station"):
            net = micros - per_step["none"]
            line += f"   net {net:6.2f} µs = {net / per_step['bare robot']:.3f} x bare robot"
        print(line)


if __name__ == "__main__":
    main()
