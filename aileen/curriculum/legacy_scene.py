"""A scene the original AILEEN's instructor saved, read as one lesson of its scripts.

The original's scripts folder holds, beside its lesson lists, single scenes its instructor
dumped while running (`current-scene-3-22-small.json`, `spatial-scene-latest.json`):

```json
{"interaction": {"content": "red cone near red box", "signal": "verify", "concept": ""},
 "scene": ["Solid {\\n recognitionColors 0.9 0.1 0.1 ... geometry Cone {...} ... description \\"Small\\"\\n}", ...]}
```

Each `scene` entry is a Webots node: its colour (`baseColor`, else `recognitionColors`: the
nearest catalogue colour),
its shape (`geometry Box|Cylinder|Cone|Sphere|Capsule`, a shape the domain declares) and its
size (`description`, when it names one) are read; its position is not (Webots' frame; the
trainer lays the scene out with its own definitions, as for every lesson of the original's).
The lesson is the one in `interaction`: one object said (a visual lesson), or a relation
between two said objects (a spatial one, its objects as the sentence names them, sized as the
scene has them). The scene's other objects stand on the table too, as the scene has them
(colour, shape, size), where the trainer finds room: a saved scene is what its table showed,
so its green sphere is a green sphere at every seed, never a random distractor. A verify
without `is_positive` is graded against the table the trainer lays out, as every lesson of
the original's without it is. Errors name the file and what was expected.
"""

from __future__ import annotations

import json
import re
from typing import Any

from aileen.curriculum.sentences import read_content
from aileen.curriculum.specs import ObjectSpec
from aileen.domain import channels
from aileen.errors import UserError
from aileen.world.catalog import PRESETS

_COLOUR = re.compile(r"(?:baseColor|recognitionColors|diffuseColor)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)")
_GEOMETRY = re.compile(r"geometry\s+([A-Za-z]+)")
_DESCRIPTION = re.compile(r'description\s+"([^"]*)"')
_NODE = re.compile(r"\s*(?:DEF\s+\S+\s+)?[A-Z][A-Za-z0-9_]*\s*\{")  # "Solid {", "DEF BOX Solid {"


def is_scene(data: Any) -> bool:
    """Is the parsed JSON a saved scene (an object with `interaction` and `scene`)?"""
    return isinstance(data, dict) and "interaction" in data and "scene" in data


class _Lines:
    """Where the saved scene's parts stand in its text (the JSON is known to be valid): the
    line of a top-level key, and of each entry of the `scene` list."""

    def __init__(self, text: str) -> None:
        self.text = text
        self.keys: dict[str, int] = {}
        self.entries: list[int] = []
        decoder = json.JSONDecoder()
        i = self._past(text.index("{") + 1, "")
        while i < len(text) and text[i] == '"':
            key, i = decoder.raw_decode(text, i)
            i = self._past(i, ":")
            self.keys.setdefault(key, self._line(i))
            if key == "scene" and text[i] == "[":
                j = self._past(i + 1, "")
                while j < len(text) and text[j] != "]":
                    self.entries.append(self._line(j))
                    _, j = decoder.raw_decode(text, j)
                    j = self._past(j, ",")
            _, i = decoder.raw_decode(text, i)
            i = self._past(i, ",")

    def _past(self, i: int, also: str) -> int:
        while i < len(self.text) and (self.text[i].isspace() or self.text[i] in also):
            i += 1
        return i

    def _line(self, i: int) -> int:
        return self.text.count("\n", 0, i) + 1

    def entry(self, k: int) -> int | None:
        return self.entries[k] if k < len(self.entries) else self.keys.get("scene")


def _object(node: Any, k: int, path: str, line: int | None = None) -> dict[str, str]:
    """The original's description of one Webots node: color, shape and, where said, size."""
    if not isinstance(node, str) or not _NODE.match(node):
        raise UserError(f"'scene' entry {k + 1} must be a Webots node as a string (\"Solid {{...}}\" with a "
                        f"baseColor and a geometry), found {json.dumps(node)[:40]}", path=path, line=line)
    colour = _COLOUR.search(node)
    geometry = _GEOMETRY.search(node)
    if colour is None or geometry is None:
        missing = "colour (baseColor, recognitionColors)" if colour is None else "geometry"
        raise UserError(f"'scene' entry {k + 1} has no {missing}; expected a Webots Solid with a "
                        f"baseColor and a geometry", path=path, line=line)
    rgb = [255 * float(v) for v in colour.groups()]
    name = min(PRESETS, key=lambda c: sum((a - b) ** 2 for a, b in zip(PRESETS[c], rgb)))
    shape = geometry.group(1).lower()
    if channels.read_value(shape, {}) != ("shape", shape):
        raise UserError(f"'scene' entry {k + 1}: unknown geometry {geometry.group(1)!r}; expected one of "
                        f"{', '.join(s.capitalize() for s in channels.get('shape').values)}", path=path, line=line)
    out = {"color": name, "shape": shape}
    said = _DESCRIPTION.search(node)
    size = channels.read_value(said.group(1).strip().lower(), {}) if said else None
    if size is not None and size[0] == "size":
        out["size"] = size[1]
    return out


def lesson_of(data: dict[str, Any], path: str, text: str | None = None) -> tuple[dict[str, Any], list[ObjectSpec]]:
    """The saved scene as a lesson of the original's list form (`legacy._lesson` reads it), and
    the scene's other objects, which stand on the table beside the lesson's (as the scene has
    them: colour, shape, size; where the trainer finds room). `text`, the file's, lets an
    error name its line."""
    lines = _Lines(text) if text is not None else None
    said = data["interaction"]
    if not isinstance(said, dict) or not isinstance(said.get("content"), str) or "signal" not in said:
        raise UserError("'interaction' must be an object with 'content' and 'signal'", path=path,
                        line=lines.keys.get("interaction") if lines else None)
    scene = data["scene"]
    if not isinstance(scene, list) or not scene:
        raise UserError("'scene' must be a non-empty list of Webots nodes", path=path,
                        line=lines.keys.get("scene") if lines else None)
    objects = [_object(node, k, path, lines.entry(k) if lines else None) for k, node in enumerate(scene)]
    content = said["content"]
    info = read_content(content)
    raw: dict[str, Any] = {"content": content, "signal": said["signal"]}
    if "is_positive" in said:
        raw["is_positive"] = said["is_positive"]
    used: list[int] = []
    if info.relation is not None and len(info.phrases) == 2:
        named = [_said_as(p.appearance, objects, used) for p in info.phrases]
        raw.update({"lesson-type": "spatial-word", "description": {"objects": named, "relation": info.relation}})
    else:
        phrase = info.phrases[0].appearance if info.phrases else {}
        k = next((k for k, o in enumerate(objects) if _fits(phrase, o)), 0)
        used.append(k)
        raw.update({"lesson-type": "visual-word", "description": {"objects": [objects[k]]}})
    others = [ObjectSpec(appearance={_CHANNEL.get(c, c): v for c, v in o.items()})
              for k, o in enumerate(objects) if k not in used]
    return raw, others


_CHANNEL = {"color": "colour"}  # the original's spelling -> the channel's name


def _fits(phrase: dict[str, str], obj: dict[str, str]) -> bool:
    return all(obj.get("color" if k == "colour" else k) == v for k, v in phrase.items())


def _said_as(phrase: dict[str, str], objects: list[dict[str, str]], used: list[int]) -> dict[str, str]:
    """The object the sentence names as the scene has it (its size too; one not named yet, its
    place added to `used`), or as said when the scene has none."""
    found = next((k for k, o in enumerate(objects) if k not in used and _fits(phrase, o)), None)
    if found is not None:
        used.append(found)
        return dict(objects[found])
    return {("color" if k == "colour" else k): v for k, v in phrase.items()}
