"""The person's clips as files a user brings and takes: BVH motion capture and clip JSON.

A scenario names its own clips under `human.clips` (files relative to the scenario: `.bvh`,
read with `hrc_drake.human.bvh`, or `.json`, as `hrc-drake clip import` writes them); they
join the built-in clips under their file names, so a tree plays one with
`<ActorAnimation animation_name="NAME"/>`.

An imported motion-capture take is moved to start where the person stands, facing forward:
the person plays a clip in place, at their own position and heading.
"""

from dataclasses import replace
from math import cos, sin
from pathlib import Path

from hrc_drake.human.bvh import bvh_to_clip
from hrc_drake.human.clip import Clip, clip_from_json, load_clips
from hrc_drake.yaml_check import InputError, did_you_mean

CLIP_SUFFIXES = (".bvh", ".json")


def at_origin(clip: Clip) -> Clip:
    """The clip turned and shifted so that its first frame stands at (0, 0) facing +x."""
    frames = clip.frames.copy()
    ix, iy, iyaw = (clip.joint_names.index(n) for n in ("base_x", "base_y", "base_yaw"))
    x0, y0, yaw0 = frames[0, [ix, iy, iyaw]]
    dx, dy = frames[:, ix] - x0, frames[:, iy] - y0
    frames[:, ix] = cos(-yaw0) * dx - sin(-yaw0) * dy
    frames[:, iy] = sin(-yaw0) * dx + cos(-yaw0) * dy
    frames[:, iyaw] -= yaw0
    return replace(clip, frames=frames)


def read_clip_file(path: Path, name: str | None = None, loop: bool = False) -> Clip:
    """A clip from a `.bvh` (placed at the origin) or a clip `.json` file; bad files raise
    InputError naming the file."""
    path = Path(path)
    if path.suffix.lower() not in CLIP_SUFFIXES:
        raise InputError(f"{path}: a clip file is .bvh or .json")
    try:
        text = path.read_text()
        if path.suffix.lower() == ".json":
            return clip_from_json(text)
        return at_origin(bvh_to_clip(text, name or path.stem, loop=loop))
    except OSError as error:
        raise InputError(f"{path}: {error.strerror}") from None
    except ValueError as error:
        raise InputError(f"{path}: not a usable clip: {error}") from None
    except (KeyError, IndexError):
        raise InputError(f"{path}: not a usable clip: the file is cut short or malformed") from None


def no_animation(name: str, clips) -> str:
    """That no clip is called `name`, with the nearest name and every one there is."""
    known = ", ".join(sorted(clips))
    return f"no animation named '{name}'{did_you_mean(name, clips)}; the person's clips: {known}"


def walks(clip: Clip) -> bool:
    """Whether the clip can carry the person along a walk: a loop that covers ground."""
    return clip.loop and clip.animation_distance > 0


def clip_catalog(files: list[str] | tuple[str, ...] = ()) -> dict[str, Clip]:
    """The built-in clips and, under their names, the clips in `files` (theirs win)."""
    clips = dict(load_clips())
    for file in files:
        clip = read_clip_file(Path(file))
        clips[clip.name] = clip
    return clips


def describe(clip: Clip) -> str:
    """One line: duration, frame rate, loop, events, description."""
    timed = sorted(clip.events.items(), key=lambda item: item[1])
    events = ", ".join(f"{name} {t:.2f} s" for name, t in timed)
    parts = [f"{clip.duration:5.2f} s at {clip.fps:g} fps"]
    parts += ["loops"] if clip.loop else []
    parts += [f"events: {events}"] if events else []
    parts += [clip.description] if clip.description else []
    return "; ".join(parts)
