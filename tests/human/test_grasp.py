"""Grasps from an object's geometry, and the carry posture that keeps hold of it."""

import math

import numpy as np
import pytest
from pydrake.math import RigidTransform

from hrc_drake.human.body import human_body
from hrc_drake.human.clip import load_clips
from hrc_drake.human.grasp import (
    PALM_GAP,
    carry_arms,
    grasp_hands,
    hold_of,
    object_center_in_holder,
    palm_targets,
)
from hrc_drake.human.messages import AnimateCommand, Grasp, Hold, MoveCommand
from hrc_drake.human.performer import Performer
from hrc_drake.human.protocol import ActorState, advance
from hrc_drake.workpieces.geometry import Solid
from tests.human.scene import Posed

CARTON = (0.3, 0.3, 0.2)


@pytest.mark.parametrize(
    ("size", "mass", "attributes", "hands"),
    [
        ((0.08, 0.08, 0.06), 0.3, {}, "right"),
        ((0.07, 0.05, 0.04), 0.2, {}, "right"),
        ((0.16, 0.12, 0.08), 0.8, {}, "both"),
        (CARTON, 3.0, {}, "both"),
        ((0.08, 0.08, 0.06), 2.5, {}, "both"),
        ((0.08, 0.08, 0.06), 0.3, {"fragile": True}, "both"),
        (CARTON, 3.0, {"grasp": "one_hand"}, "right"),
    ],
)
def test_hands_follow_from_size_mass_and_attributes(size, mass, attributes, hands):
    assert grasp_hands(size, mass, attributes) == hands


@pytest.mark.parametrize("yaw", [0.0, 0.5, math.pi / 2 + 0.3])
def test_palms_go_on_the_two_faces_that_face_the_persons_sides(yaw):
    grasp = Grasp("both", (0.6, 0.1, 0.8), yaw, (0.34, 0.3, 0.24))
    targets = palm_targets(grasp, heading=0.0)
    box = Solid("box", grasp.size)
    X_inverse = np.array([[math.cos(yaw), math.sin(yaw)], [-math.sin(yaw), math.cos(yaw)]])
    for side, sign in (("left", 1), ("right", -1)):
        position, _ = targets[side]
        local = np.array([*X_inverse @ (position[:2] - grasp.center[:2]), 0.0])
        assert box.signed_distance_to(local) == pytest.approx(PALM_GAP, abs=1e-9)  # just off
        assert sign * (position[1] - grasp.center[1]) > 0  # on the person's own side


ELBOW_HEIGHT = 0.630
"""Elbow height over body height (Drillis and Contini, in Winter; docs/human-body.md)."""
HIP_HEIGHT = 0.530
CLOSE_TO_THE_BODY = 0.04
"""m: the gap between a box carried close to the body and the belly (HSE INDG143: the
load close to the waist, hugged as close as possible to the body; docs/realism.md)."""
TRUNK = ("pelvis", "abdomen", "chest", "thigh")


def _elbow_flexion(body, q, side: str) -> float:
    """Degrees the elbow bends, from where shoulder, elbow and wrist are."""
    shoulder, elbow, wrist = (
        body.frame_pose(f"{side}_{frame}", q).translation()
        for frame in ("upper_arm", "forearm", "hand")
    )
    upper, lower = elbow - shoulder, wrist - elbow
    cosine = upper @ lower / np.linalg.norm(upper) / np.linalg.norm(lower)
    return math.degrees(math.acos(cosine))


@pytest.mark.parametrize("size", [CARTON, (0.34, 0.34, 0.24)], ids=["carton", "crate"])
def test_a_box_is_carried_as_people_carry_it(size):
    """Between the palms, close to the body at about waist height, the elbows bent."""
    body = human_body()
    hold = Hold("both", size)
    q = carry_arms(body, hold).over(body.standing_pose())
    left, right = (body.frame_pose(f"{s}_hand_grasp", q).translation() for s in ("left", "right"))
    assert np.linalg.norm(left - right) == pytest.approx(hold.size[1] + 2 * PALM_GAP, abs=0.01)
    center = (left + right) / 2 + object_center_in_holder(hold)  # the person faces +x
    height = body.skeleton.height
    assert HIP_HEIGHT * height <= center[2] <= ELBOW_HEIGHT * height
    gap = Posed(q, [(size, RigidTransform(center))]).distance(0, TRUNK)
    assert 0.0 < gap <= CLOSE_TO_THE_BODY, f"{gap:.3f} m from the body"
    for side in ("left", "right"):
        assert 70.0 <= _elbow_flexion(body, q, side) <= 110.0


def _palm_spacing(performer, state, t):
    body = performer.body
    left, right = (
        body.frame_pose(f"{s}_hand_grasp", state.pose).translation() for s in ("left", "right")
    )
    return float(np.linalg.norm(left - right))


def test_the_palms_keep_hold_through_pick_turn_walk_and_standing():
    """After the grasp the palms stay as far apart as the carton is wide, however the
    person moves: lifting, turning round, walking, standing."""
    performer = Performer(human_body(), load_clips())
    grasp = Grasp("both", (0.55, 0.0, 0.85), 0.0, CARTON)
    hold = hold_of(grasp, 0.0)
    state = advance(performer, ActorState(), 0.0, {})
    schedule = {
        0.1: AnimateCommand(1, "pick_table", grasp=grasp),
        3.0: MoveCommand(2, (-1.5, 1.0, 0.0), hold=hold),
    }
    grasped = 0.1 + load_clips()["pick_table"].events["grasp"]
    spacings = []
    for k in range(1, int(9.0 * 60)):
        t = k / 60
        command = schedule.get(round(t, 2)) if round(t * 60) % 6 == 0 else None
        state = advance(performer, state, t, {"human": command} if command else {})
        if t > grasped + 0.05:
            spacings.append(_palm_spacing(performer, state, t))
    assert state.state == "IDLE" and state.results.last.outcome == "succeeded"
    assert max(abs(s - CARTON[1]) for s in spacings) < 0.02
