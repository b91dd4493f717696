"""The person as their poses are computed: body, clips and the map they walk by.

Every pose the person takes (hrc_drake.human.protocol) comes from the same few unchanging
things: the body's joint layout and legs, the motion clips it plays, and the cell's
navigation map that walks go round and the hands keep out of. `Performer` holds them
together, so that the segments, activities and protocol take one argument for them;
`place` puts a clip's pose into the world, `carried` puts the arms into the carry posture.
"""

from dataclasses import dataclass
from functools import cached_property
from math import cos, sin

import numpy as np

from hrc_drake.human.body import HumanBody, human_body
from hrc_drake.human.clip import Clip, scaled_clips
from hrc_drake.human.furniture import Furniture
from hrc_drake.human.grasp import CarryArms
from hrc_drake.human.legs import Legs
from hrc_drake.human.navigation import NavigationMap
from hrc_drake.human.stepping import GaitProfile, gait_profile

IDLE_CLIP = "idle"
"""The clip the person stands at ease in between activities."""


@dataclass(frozen=True)
class Performer:
    """What every pose computation needs: the body's joint layout and the clips; and the
    cell's navigation map, which walks go round (None: walk straight). Never changes during
    a run, so what it derives (root indices, legs, standing pose, gait profiles) is worked
    out once."""

    body: HumanBody
    clips: dict[str, Clip]
    navigation: NavigationMap | None = None

    def index(self, name: str) -> int:
        return self.body.index(name)

    @cached_property
    def root(self) -> tuple[int, int, int]:
        """Indices of base_x, base_y and base_yaw, looked up once: every pose places the root."""
        return self.index("base_x"), self.index("base_y"), self.index("base_yaw")

    @cached_property
    def legs(self) -> Legs:
        """The legs in closed form (walking places the feet on its steps)."""
        return Legs(self.body)

    @cached_property
    def standing(self) -> np.ndarray:
        """Standing at ease (the idle clip's first pose, at the origin): where walks set off
        from and come to rest in."""
        return self.clips[IDLE_CLIP].sample(0.0)

    def gait(self, clip: Clip) -> GaitProfile:
        return gait_profile(self.legs, clip)

    @cached_property
    def furniture(self) -> Furniture:
        """The cell's fixed geometry the hands work on and keep out of (the navigation
        map's pieces)."""
        return Furniture(tuple(self.navigation.obstacles) if self.navigation else ())


def sized_performer(
    height: float, mass: float, clips: dict[str, Clip], navigation: NavigationMap | None = None
) -> Performer:
    """The person of `height` and `mass` with `clips` (taken by a person of DEFAULT_HEIGHT)
    scaled to them: the run's person and the one `validate` plans for are built here, so
    they are the same (validate once planned a 5th-percentile man's body with a 1.75 m
    person's clips, and found no fault in a pick the run refused 55 times, the head 2.5 cm
    in a rack, a user's cell: #26)."""
    return Performer(human_body(height, mass), scaled_clips(clips, height), navigation)


def place(performer: Performer, q: np.ndarray, x: float, y: float, yaw: float) -> np.ndarray:
    """A clip pose (root in the clip frame) put into the world at (x, y) facing yaw."""
    ix, iy, iyaw = performer.root
    placed = q.copy()
    qx, qy = float(q[ix]), float(q[iy])
    c, s = cos(yaw), sin(yaw)
    placed[ix] = x + c * qx - s * qy
    placed[iy] = y + s * qx + c * qy
    placed[iyaw] = yaw + float(q[iyaw])
    return placed


def carried(q: np.ndarray, carry: CarryArms | None) -> np.ndarray:
    """`q` with the arms in the carry posture, when something is carried."""
    return q if carry is None else carry.over(q)
