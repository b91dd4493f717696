"""How the workpieces world starts and how each update changes it, in order.

`next_world` maps (world, time, commands, holder frames) to the next world:

1. free objects move on with the velocity planned at the previous update;
2. held objects follow their holder's grasp frame with the offset they had when grasped;
3. each issuer's new command is carried out (in the order of the issuers;
   hrc_drake.workpieces.commands);
4. objects past the end of a removing belt leave;
5. free objects find what they rest on and plan their motion for the next period
   (hrc_drake.workpieces.settling).

Steps 1 and 2 happen as the update's working copy (hrc_drake.workpieces.step) is made.
An update that would change nothing but the holders' samples is not needed (`still`): no new
command, and every object at rest on something, a belt's queue included.
"""

from hrc_drake.messages import newer_commands
from hrc_drake.workpieces.commands import execute
from hrc_drake.workpieces.layouts import initial_placements
from hrc_drake.workpieces.messages import FIRST_ID, WorkpiecesCommand
from hrc_drake.workpieces.settling import remove_past_belt_ends, settle
from hrc_drake.workpieces.step import Step
from hrc_drake.workpieces.world import LAYOUT_STREAM, Sampled, Workcell, World


def initial_world(cell: Workcell) -> World:
    """The scenario's initial objects, resting where they fall."""
    step = Step(cell, _empty_world(), 0.0, {})
    for placement in initial_placements(cell.config, cell.random(LAYOUT_STREAM)):
        if step.create(placement) is None:
            raise ValueError(f"more initial objects of type '{placement.type}' than slots")
    settle(step, instantly=True)
    return step.world()


def next_world(
    cell: Workcell,
    world: World,
    now: float,
    commands: dict[str, WorkpiecesCommand | tuple | None],
    holder_frames: dict[str, Sampled],
) -> World:
    """The world at `now` after `world`: each issuer's port value (None, a command or a
    tuple of recent commands) and each present holder's grasp frame (`holder_frames`)."""
    step = Step(cell, world, now, holder_frames)
    for issuer_index, issuer in enumerate(cell.issuers):
        for command in newer_commands(commands.get(issuer), world.seen.get(issuer, -1)):
            execute(step, issuer, issuer_index, command)
    remove_past_belt_ends(step)
    settle(step, instantly=False)
    return step.world()


def still(
    cell: Workcell, world: World, commands: dict[str, WorkpiecesCommand | tuple | None]
) -> bool:
    """Whether the next update can be left out: no issuer has a new command, and no object
    is held, falling or moving. Objects queued on a belt count as at rest: a belt's plan
    depends only on where its riders are, so riders that stand still stay where they are
    until a command changes the world. The holders' samples go stale meanwhile: a holder's
    first sample after the pause has no velocity (`hrc_drake.workpieces.step.PAUSE`)."""
    return world.at_rest and not any(
        newer_commands(commands.get(i), world.seen.get(i, -1)) for i in cell.issuers
    )


def _empty_world() -> World:
    return World(0.0, {}, FIRST_ID, {}, {}, {})
