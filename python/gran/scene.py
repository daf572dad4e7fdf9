"""Scenes from Python: a scene file, a dict or YAML text, changed key by key, validated by the
same loader as `gran check` (every key, type, range and cross-reference; errors name the file,
line, column and key).

    scene = gran.Scene.load("studies/demo/vibrated-mixture-2d.yaml")
    scene.set("species.0.mass", 5).set("run.measurement", 2000)
    facts = scene.check()          # places the particles; raises gran.SceneError
    print(facts["particles"], scene.resolved["box"])
"""
from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Iterable, Optional

import yaml


class SceneError(ValueError):
    """A scene gran refuses, with where and why.

    `str(e)` is gran's message ("file:line:column: key: what was expected"); the parts are
    attributes, None when the message does not carry them: `file`, `line`, `column` (1-based),
    `key` (the dotted key path, e.g. "species[1].mass", or the `--set` assignment that set it)
    and `reason` (the message after the key).
    """

    # "file:line:column: key: reason" or "--set 'assignment': key: reason"
    _LOCATED = re.compile(r"^(?P<file>.+?):(?P<line>\d+):(?P<column>\d+): (?P<rest>.*)$", re.S)
    _OVERRIDE = re.compile(r"^--set '(?P<assignment>.*?)': (?P<rest>.*)$", re.S)
    _KEY = re.compile(r"^(?P<key>[A-Za-z_][\w.\[\]-]*): (?P<reason>.*)$", re.S)

    def __init__(self, message: str):
        super().__init__(message)
        self.file: Optional[str] = None
        self.line: Optional[int] = None
        self.column: Optional[int] = None
        self.key: Optional[str] = None
        self.reason: str = message
        rest = message
        if m := self._LOCATED.match(message):
            self.file, self.line, self.column = m["file"], int(m["line"]), int(m["column"])
            rest = m["rest"]
        elif m := self._OVERRIDE.match(message):
            self.file = "--set " + m["assignment"]
            rest = m["rest"]
        if m := self._KEY.match(rest):
            self.key, self.reason = m["key"], m["reason"]
        else:
            self.reason = rest


def _native():
    from gran import native  # noqa: PLC0415  (the compiled module is optional for the reader)

    return native()


def yaml_value(value: Any) -> str:
    """A Python value as the YAML text of a `--set key=value` override."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return value
    return yaml.safe_dump(value, default_flow_style=True, width=1 << 30).strip()


class Scene:
    """A scene: its YAML text (as in a file), where it came from, and the overrides applied to it
    (`gran run --set`). Validation is gran's own (the C++ loader); errors raise SceneError."""

    def __init__(self, text: str, path: str = "<string>", overrides: Iterable[str] = ()):
        """A scene from YAML text; `path` names it in errors (and relative paths inside it)."""
        self._text = text
        self._path = str(path)
        self._overrides = list(overrides)
        self._loaded = None

    @classmethod
    def load(cls, path, overrides: Iterable[str] = ()) -> "Scene":
        """The scene file at `path` (validated at once; SceneError naming the file otherwise)."""
        p = Path(path)
        if p.is_dir():
            raise SceneError(f"{p}: is a directory, not a scene file")
        try:
            text = p.read_text()
        except OSError as e:
            raise SceneError(f"{p}: cannot read the scene file ({e.strerror})") from None
        scene = cls(text, str(p), overrides)
        scene.native()
        return scene

    @classmethod
    def from_dict(cls, scene: dict, name: str = "<dict>") -> "Scene":
        """A scene from a dict shaped like a scene file (validated at once). Errors name `name`
        and the line of the dict's YAML form (`Scene.text`)."""
        s = cls(yaml.safe_dump(scene, sort_keys=False), name)
        s.native()
        return s

    @classmethod
    def from_yaml(cls, text: str, name: str = "<string>") -> "Scene":
        """A scene from YAML text (validated at once)."""
        s = cls(text, name)
        s.native()
        return s

    def set(self, key: str, value: Any) -> "Scene":
        """Sets a dotted key ("species.0.mass", "run.measurement") as `gran run --set` does and
        validates the result; returns the scene, so calls chain. A refused value raises
        SceneError and leaves the scene as it was."""
        assignment = f"{key}={yaml_value(value)}"
        before = list(self._overrides)
        # A key set again replaces its earlier assignment (a sweep does not pile them up).
        self._overrides = [a for a in self._overrides if a.split("=", 1)[0] != key]
        self._overrides.append(assignment)
        self._loaded = None
        try:
            self.native()
        except SceneError:
            self._overrides = before
            self._loaded = None
            raise
        return self

    def check(self) -> dict:
        """Everything `gran check` does short of measuring speed: validates, places the particles
        and builds every plugin. Returns facts (dimension, particles, species, packing_fraction,
        box_length, periodic, engine, seed, and `cost`, the estimated cost of the run)."""
        n = self.native()
        with _scene_errors():
            n.check()
        return dict(n.facts())

    @property
    def text(self) -> str:
        """The YAML text the scene was made from (before overrides)."""
        return self._text

    @property
    def path(self) -> str:
        """The file the scene came from ("<dict>", "<string>" otherwise); errors name it."""
        return self._path

    @property
    def overrides(self) -> list:
        """The `key=value` assignments applied, in order."""
        return list(self._overrides)

    @property
    def resolved(self) -> dict:
        """The fully resolved scene (every default filled in), as a run records it."""
        return yaml.safe_load(self.native().resolved())

    def to_yaml(self) -> str:
        """The resolved scene as YAML text (a scene file that runs the same)."""
        return self.native().resolved()

    def native(self):
        """The validated scene of the compiled module (loaded once per change)."""
        if self._loaded is None:
            with _scene_errors():
                self._loaded = _native().load_scene(self._text, self._path, self._overrides)
        return self._loaded

    def __repr__(self) -> str:
        extra = f", {len(self._overrides)} overrides" if self._overrides else ""
        return f"<gran.Scene {self._path}{extra}>"


class _scene_errors:
    """Turns the compiled module's scene errors into SceneError (with its parsed parts)."""

    def __enter__(self):
        return self

    def __exit__(self, kind, error, tb):
        if kind is not None and kind.__name__ == "SceneError" and kind is not SceneError:
            raise SceneError(str(error)) from None
        return False
