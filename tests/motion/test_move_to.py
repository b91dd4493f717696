"""MoveTo reaches tool targets across each variant's workspace, around obstacles."""

import numpy as np
import pytest
from pydrake.math import RigidTransform, RollPitchYaw

from hrc_drake.iisy import VARIANTS
from hrc_drake.messages import FAILED, SUCCEEDED
from hrc_drake.motion.messages import MoveTo
from tests.motion.motion_helpers import PEDESTAL_TOP, build_station, make_scenario

TOOL_DOWN = RollPitchYaw(np.pi, 0.0, 0.0)


def workspace_targets(variant: str) -> list[RigidTransform]:
    """Targets at fractions of the reach: in front, to the side, turned and tilted tools."""
    reach = VARIANTS[variant].reach
    return [
        RigidTransform(
            RollPitchYaw(np.pi, 0.0, np.pi / 4), [0.55 * reach, 0.3 * reach, PEDESTAL_TOP + 0.15]
        ),
        RigidTransform(
            RollPitchYaw(np.radians(150), 0.0, 0.0),
            [0.2 * reach, -0.55 * reach, PEDESTAL_TOP + 0.25],
        ),
    ]


def pose_error(actual: RigidTransform, target: RigidTransform) -> tuple[float, float]:
    """(position error in m, rotation error in degrees)."""
    distance = np.linalg.norm(actual.translation() - target.translation())
    angle = actual.rotation().InvertAndCompose(target.rotation()).ToAngleAxis().angle()
    return distance, np.degrees(angle)


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_move_to_reaches_targets_across_the_workspace(variant):
    station = build_station(make_scenario(variant))
    for seq, target in enumerate(workspace_targets(variant), start=1):
        station.command(MoveTo(seq=seq, pose=target))
        assert station.run_until_finished(seq) == SUCCEEDED, station.status().results.last.reason
        distance, angle = pose_error(station.tool_pose(), target)
        assert distance < 2e-3 and angle < 1.0, (distance, angle)
    station.command(
        MoveTo(seq=9, pose=RigidTransform(TOOL_DOWN, [2.0 * VARIANTS[variant].reach, 0, 1]))
    )
    assert station.run_until_finished(9) == FAILED
    assert "unreachable" in station.status().results.last.reason


def test_unreachable_orientation_fails_with_reason():
    station = build_station(make_scenario())
    inside_pedestal = RigidTransform(TOOL_DOWN, [0.0, 0.0, PEDESTAL_TOP - 0.1])
    station.command(MoveTo(seq=1, pose=inside_pedestal))
    assert station.run_until_finished(1) == FAILED
    assert "unreachable" in station.status().results.last.reason
