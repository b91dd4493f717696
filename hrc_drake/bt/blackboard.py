"""Blackboards: one per tree or SubTree instance, linked to their parent by remapping."""

from __future__ import annotations

from typing import Any

from .errors import BTError
from .ports import coerce, type_name


class _Unset:
    def __repr__(self) -> str:
        return "UNSET"


UNSET: Any = _Unset()


class Entry:
    """A typed slot. Entries are never removed, only unset, so nodes may hold them."""

    __slots__ = ("value", "type", "sequence_id")

    def __init__(self, value: Any = UNSET, py_type: Any = None):
        self.value = value
        self.type = py_type
        self.sequence_id = 0

    def assign(self, value: Any) -> None:
        try:
            self.value = coerce(value, self.type)
        except ValueError as error:
            raise BTError(str(error)) from None
        self.sequence_id += 1


class Blackboard:
    """Key/value store of one tree instance.

    ``remap`` maps a key of this blackboard to a key of the parent (a SubTree port
    ``port="{key}"``); with ``autoremap`` every key not starting with ``_`` is shared
    with the parent. ``@key`` always means the root blackboard.
    """

    def __init__(
        self,
        parent: Blackboard | None = None,
        remap: dict[str, str] | None = None,
        autoremap: bool = False,
    ):
        self.parent = parent
        self.root: Blackboard = parent.root if parent is not None else self
        self._remap = remap or {}
        self._autoremap = autoremap
        self._entries: dict[str, Entry] = {}
        self._initial: dict[str, tuple[Any, Any]] = {}

    def entry(self, key: str, create: bool = False) -> Entry | None:
        """The entry that ``key`` designates here, following remaps; None if absent."""
        found = self._entries.get(key)
        if found is not None:
            return found
        if key.startswith("@"):
            return self.root.entry(key[1:], create)
        outer_key = self._remap.get(key)
        if outer_key is not None:
            return self.parent.entry(outer_key, create)
        if self._autoremap and not key.startswith("_"):
            return self.parent.entry(key, create)
        if not create:
            return None
        found = self._entries[key] = Entry()
        return found

    def declare(self, key: str, py_type: Any) -> Entry:
        """Create the entry if needed and fix its type; a different type is an error."""
        found = self.entry(key, create=True)
        if py_type is None or found.type == py_type:
            return found
        if found.type is not None:
            raise BTError(
                f"blackboard entry '{key}' has type {type_name(found.type)}, "
                f"but is used here as {type_name(py_type)}"
            )
        found.type = py_type
        if found.value is not UNSET:
            found.assign(found.value)
        return found

    def get(self, key: str, default: Any = UNSET) -> Any:
        found = self.entry(key)
        if found is None or found.value is UNSET:
            if default is not UNSET:
                return default
            raise BTError(f"blackboard entry '{key}' is not set")
        return found.value

    def set(self, key: str, value: Any) -> None:
        self.entry(key, create=True).assign(value)

    def set_local(self, key: str, value: Any) -> None:
        """Set an entry of this blackboard itself, even where ``key`` would otherwise
        reach the parent by autoremapping (a SubTree's literal port)."""
        found = self._entries.setdefault(key, Entry())
        found.assign(value)

    def unset(self, key: str) -> None:
        found = self.entry(key)
        if found is not None:
            found.value = UNSET

    def has(self, key: str) -> bool:
        found = self.entry(key)
        return found is not None and found.value is not UNSET

    def local_entries(self) -> dict[str, Entry]:
        """The entries stored in this blackboard itself (set or not), by key."""
        return dict(self._entries)

    def keys(self) -> list[str]:
        """Keys stored in this blackboard itself (not in its parents)."""
        return [key for key, found in self._entries.items() if found.value is not UNSET]

    def as_dict(self) -> dict[str, Any]:
        return {key: self._entries[key].value for key in self.keys()}

    def snapshot(self) -> dict[str, Any]:
        """Every entry stored here, unset ones as None, lists copied: a copy that another
        thread may read while the tree runs on (values are replaced, never mutated, except
        lists such as a Loop's queue)."""
        return {
            key: None
            if found.value is UNSET
            else list(found.value)
            if isinstance(found.value, list)
            else found.value
            for key, found in self._entries.items()
        }

    def remember_initial_state(self) -> None:
        self._initial = {key: (e.value, e.type) for key, e in self._entries.items()}

    def restore_initial_state(self) -> None:
        """Back to the state recorded after construction; later entries are dropped."""
        for key in list(self._entries):
            if key not in self._initial:
                del self._entries[key]
        for key, (value, py_type) in self._initial.items():
            found = self._entries[key]
            found.value, found.type, found.sequence_id = value, py_type, 0
