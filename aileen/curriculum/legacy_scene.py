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


def is_scene(data: Any) -> bool:
    """Is the parsed JSON a saved scene (an object with `interaction` and `scene`)?"""
    return isinstance(data, dict) and "interaction" in data and "scene" in data


def _object(node: Any, k: int, path: str) -> dict[str, str]:
    """The original's description of one Webots node: color, shape and, where said, size."""
    if not isinstance(node, str):
        raise UserError(f"'scene' entry {k + 1} must be a Webots node as a string (\"Solid {{...}}\")", path=path)
    colour = _COLOUR.search(node)
    geometry = _GEOMETRY.search(node)
    if colour is None or geometry is None:
        missing = "colour (baseColor, recognitionColors)" if colour is None else "geometry"
        raise UserError(f"'scene' entry {k + 1} has no {missing}; expected a Webots Solid with a "
                        f"baseColor and a geometry", path=path)
    rgb = [255 * float(v) for v in colour.groups()]
    name = min(PRESETS, key=lambda c: sum((a - b) ** 2 for a, b in zip(PRESETS[c], rgb)))
    shape = geometry.group(1).lower()
    if channels.read_value(shape, {}) != ("shape", shape):
        raise UserError(f"'scene' entry {k + 1}: unknown geometry {geometry.group(1)!r}; expected one of "
                        f"{', '.join(s.capitalize() for s in channels.get('shape').values)}", path=path)
    out = {"color": name, "shape": shape}
    said = _DESCRIPTION.search(node)
    size = channels.read_value(said.group(1).strip().lower(), {}) if said else None
    if size is not None and size[0] == "size":
        out["size"] = size[1]
    return out


def lesson_of(data: dict[str, Any], path: str) -> tuple[dict[str, Any], list[ObjectSpec]]:
    """The saved scene as a lesson of the original's list form (`legacy._lesson` reads it), and
    the scene's other objects, which stand on the table beside the lesson's (as the scene has
    them: colour, shape, size; where the trainer finds room)."""
    said = data["interaction"]
    if not isinstance(said, dict) or not isinstance(said.get("content"), str) or "signal" not in said:
        raise UserError("'interaction' must be an object with 'content' and 'signal'", path=path)
    scene = data["scene"]
    if not isinstance(scene, list) or not scene:
        raise UserError("'scene' must be a non-empty list of Webots nodes", path=path)
    objects = [_object(node, k, path) for k, node in enumerate(scene)]
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
