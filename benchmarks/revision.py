"""A module's code as it was at a git revision, loaded beside the working tree's, so that a
benchmark can time old and new code on the same run in one process."""

import subprocess
import sys
import types
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def module_at(revision: str, path: str, name: str, replacing: dict | None = None):
    """The module at `path` (from the repository's root) as it was at `revision`, named
    `name`; `replacing` stands in for the modules it imports while it is loaded
    (name: module)."""
    source = subprocess.run(
        ["git", "show", f"{revision}:{path}"], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout
    module = types.ModuleType(name)
    saved = {key: sys.modules.get(key) for key in replacing or {}}
    sys.modules.update(replacing or {})
    try:
        exec(compile(source, f"{revision}:{path}", "exec"), module.__dict__)
    finally:
        sys.modules.update(saved)
    return module
