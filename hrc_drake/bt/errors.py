"""The engine's single exception type, whose message is one self-contained line."""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class BTError(Exception):
    """A tree that cannot be loaded, validated or ticked.

    The message reads ``file:line: tree 'ID', node 'path', port 'name': problem (did you
    mean 'X'?)``; parts that are unknown are left out, so a CLI can print it as is.
    """

    def __init__(
        self,
        problem: str,
        *,
        file: str | None = None,
        line: int | None = None,
        tree: str | None = None,
        node: str | None = None,
        port: str | None = None,
        suggestion: str | None = None,
    ):
        self.problem = problem
        self.file = file
        self.line = line
        self.tree = tree
        self.node = node
        self.port = port
        self.suggestion = suggestion
        super().__init__(self.message)

    @property
    def place(self) -> str:
        """`tree 'ID', node 'path', port 'name'` (the parts that are known)."""
        return ", ".join(
            f"{label} '{value}'"
            for label, value in (("tree", self.tree), ("node", self.node), ("port", self.port))
            if value is not None
        )

    @property
    def message(self) -> str:
        where = self.place
        location = (self.file or "<unknown>") + (f":{self.line}" if self.line else "")
        text = f"{location}: {where + ': ' if where else ''}{self.problem}"
        if self.suggestion:
            text += f" (did you mean '{self.suggestion}'?)"
        return " ".join(text.split("\n"))

    def located(self, **where) -> BTError:
        """Return a copy with the missing location fields filled in from ``where``."""
        fields = {
            key: getattr(self, key) if getattr(self, key) is not None else where.get(key)
            for key in ("file", "line", "tree", "node", "port")
        }
        return BTError(self.problem, suggestion=self.suggestion, **fields)


def closest(name: str, candidates: Iterable[str]) -> str | None:
    """The most similar candidate to ``name``, for "did you mean" hints."""
    matches = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.5)
    return matches[0] if matches else None
