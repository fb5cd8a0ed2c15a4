"""The original AILEEN lesson scripts (JSON), read into the same records as our TOML files.

A script is a JSON list of lessons such as

```json
{"lesson-type": "spatial-word", "signal": "inform", "distractors": 1,
 "content": "blue cone right of red cylinder",
 "description": {"objects": [{"color": "blue", "shape": "cone"},
                             {"color": "red", "shape": "cylinder"}],
                 "relation": "right-of"}}
```

The mapping (docs/lessons.md has the table): `description` is what stands on the table (for a
relation, the first object stands in it to the second), `content` what the trainer says;
`is_positive: "False"` marks an exam whose right answer is a failure. The original's spellings
are accepted: `color`, relation keys `left-of`/`right-of`/`front-of`/`behind`, shape `cube`,
action descriptions with `<obj1>` placeholders and `trace-actions`. Webots-only fields
(`rgb`, `position` in Webots' frame, `initial_configuration`, `language`) are ignored: the
trainer lays scenes out with its own definitions.

Errors name the file, the line where the lesson (or the field) starts, and the 1-based lesson
number: `script.json:14: lesson 3: 'signal' must be one of inform, verify, react`.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from aileen.domain import relations
from aileen.curriculum.lesson import (
    SIGNALS,
    ActionSpec,
    Curriculum,
    Lesson,
    ObjectSpec,
    Source,
    Step,
    check_colour,
    check_lesson,
    check_shape,
    parse_action,
    read_lesson_text,
)
from aileen.errors import UserError
from aileen.world import catalog

LESSON_TYPES: tuple[str, ...] = ("visual-word", "spatial-word", "action-word")
LESSON_KEYS: tuple[str, ...] = ("lesson-type", "content", "description", "signal", "distractors",
                                "is_positive", "comment")
IGNORED_OBJECT_KEYS: tuple[str, ...] = ("rgb", "position", "translation")
IGNORED_DESCRIPTION_KEYS: tuple[str, ...] = ("initial_configuration", "language")


def _spans(text: str) -> list[tuple[int, int]]:
    """Character spans of the top-level list's elements (the text is known to be valid JSON)."""
    decoder = json.JSONDecoder()
    spans: list[tuple[int, int]] = []
    i = text.index("[") + 1
    n = len(text)
    while True:
        while i < n and text[i] in " \t\r\n,":
            i += 1
        if i >= n or text[i] == "]":
            return spans
        _, end = decoder.raw_decode(text, i)
        spans.append((i, end))
        i = end


class _Where:
    """Locates a lesson and the fields inside it in the script text."""

    def __init__(self, text: str, path: str, index: int, span: tuple[int, int] | None) -> None:
        self.text = text
        self.span = span
        line = text.count("\n", 0, span[0]) + 1 if span else None
        self.source = Source(path, line, index + 1)

    def line_of(self, *needles: str) -> int | None:
        """Line of the first needle found (in order, each after the previous) inside the lesson."""
        if self.span is None:
            return None
        pos = self.span[0]
        found = False
        for needle in needles:
            at = self.text.find(needle, pos, self.span[1])
            if at < 0:
                break
            pos, found = at, True
        return self.text.count("\n", 0, pos) + 1 if found else self.source.line

    def error(self, message: str, *needles: str) -> UserError:
        return self.source.error(message, line=self.line_of(*needles) if needles else None)


def _no_duplicates(pairs: list[tuple[str, object]]) -> dict[str, object]:
    out: dict[str, object] = {}
    for k, v in pairs:
        if k in out:
            raise ValueError(f"duplicate key {k!r}")
        out[k] = v
    return out


def loads(text: str, path: str = "<string>") -> Curriculum:
    """Parse an original-format script; every error is a `UserError` naming the lesson and field."""
    try:
        data = json.loads(text, object_pairs_hook=_no_duplicates)
    except json.JSONDecodeError as exc:
        raise UserError(f"invalid JSON: {exc.msg} (column {exc.colno})", path=path, line=exc.lineno) from None
    except RecursionError:
        raise UserError("nested too deeply to be a lesson script", path=path) from None
    except ValueError as exc:  # a duplicate key: one of the two values would be dropped unseen
        raise UserError(f"invalid lesson script: {exc}", path=path) from None
    if not isinstance(data, list):
        raise UserError("expected a JSON list of lessons ([{...}, ...])", path=path, line=1)
    if not data:
        raise UserError("no lessons; expected a JSON list with at least one lesson", path=path, line=1)
    spans = _spans(text)
    lessons = []
    for i, raw in enumerate(data):
        where = _Where(text, path, i, spans[i] if i < len(spans) else None)
        lessons.append(_lesson(raw, where))
    return Curriculum(lessons=lessons, seed=0, title=Path(path).stem, path=path)


def load(path: str | Path) -> Curriculum:
    """Read an original AILEEN `.json` lesson script."""
    return loads(read_lesson_text(path), str(path))


def _field(name: str) -> str:
    return f'"{name}"'


def _lesson(raw: Any, where: _Where) -> Lesson:
    if not isinstance(raw, dict):
        raise where.error("expected an object with 'lesson-type', 'content', 'description', 'signal'")
    for key in raw:
        if key not in LESSON_KEYS:
            raise where.error(f"unknown field {key!r}; expected one of: {', '.join(LESSON_KEYS)}", _field(key))
    kind = raw.get("lesson-type")
    if kind not in LESSON_TYPES:
        if "lesson-type" not in raw:
            raise where.error(f"missing 'lesson-type'; expected one of {', '.join(LESSON_TYPES)}")
        raise where.error(f"'lesson-type' must be one of {', '.join(LESSON_TYPES)} (got {kind!r})",
                          _field("lesson-type"))
    signal = raw.get("signal")
    if signal not in SIGNALS:
        if "signal" not in raw:
            raise where.error(f"missing 'signal'; expected one of {', '.join(SIGNALS)}")
        raise where.error(f"'signal' must be one of {', '.join(SIGNALS)} (got {signal!r})", _field("signal"))
    distractors = raw.get("distractors", 0)
    if distractors is None:
        distractors = 0
    if not isinstance(distractors, int) or isinstance(distractors, bool) or distractors < 0:
        raise where.error("'distractors' must be a whole number >= 0", _field("distractors"))
    expect = None
    if "is_positive" in raw:
        value = str(raw["is_positive"]).strip().lower()
        if value not in ("true", "false"):
            raise where.error("'is_positive' must be \"True\" or \"False\"", _field("is_positive"))
        expect = "success" if value == "true" else "failure"
    content = raw.get("content")
    if content is not None and (not isinstance(content, str) or not content.strip()):
        raise where.error("'content' must be a non-empty string", _field("content"))
    note = raw.get("comment", "")
    if not isinstance(note, str):
        raise where.error("'comment' must be a string", _field("comment"))
    description = raw.get("description")
    if description is not None and not isinstance(description, dict):
        raise where.error("'description' must be an object", _field("description"))

    relation: str | None = None
    action: ActionSpec | None = None
    demonstration: list[Step] | None = None
    if kind == "visual-word":
        objects = _visual_objects(description, where)
        said = objects[0].describe() if objects[0].shape or objects[0].colour else None
    elif kind == "spatial-word":
        if description is None:
            raise where.error("a spatial-word lesson needs 'description' with 'objects' and 'relation'")
        objects = _objects(description.get("objects"), description, where)
        if len(objects) != 2:
            raise where.error("'description.objects' must list two objects for a spatial-word lesson",
                              _field("description"), _field("objects"))
        relation = _relation(description.get("relation"), where)
        said = f"{objects[0].describe()} {relation} {objects[1].describe()}"
    else:
        if description is None:
            raise where.error("an action-word lesson needs 'description' with 'objects' and 'relations'")
        objects = _objects(description.get("objects"), description, where)
        if len(objects) != 2:
            raise where.error("'description.objects' must list two objects: the one moved, then the reference",
                              _field("description"), _field("objects"))
        action = _action(description, where)
        said = f"{action.verb} {objects[0].describe()} {action.relation} {objects[1].describe()}"
        if signal != "react":
            demonstration = _trace(description, action, where)
    if content is None:
        if said is None:
            raise where.error("missing 'content' and the description does not say what to call the object")
        content = said
    lesson = Lesson(signal=signal, content=" ".join(content.split()), objects=objects, relation=relation,
                    distractors=distractors, demonstration=demonstration, source=where.source, action=action,
                    expect=expect, note=note)
    check_lesson(lesson)
    return lesson


def _object(raw: Any, where: _Where, label: str) -> ObjectSpec:
    if not isinstance(raw, dict):
        raise where.error(f"{label} must be an object like {{\"color\": \"red\", \"shape\": \"box\"}}",
                          _field("description"))
    for key in raw:
        if key not in ("color", "colour", "shape", "size", *IGNORED_OBJECT_KEYS):
            raise where.error(f"{label}: unknown field {key!r}; expected color, shape, size", _field(key))
    colour = raw.get("color", raw.get("colour"))
    shape = raw.get("shape")
    size = raw.get("size")
    try:
        colour = check_colour(colour) if colour is not None else None
    except (UserError, AttributeError):
        raise where.error(f"{label}: unknown colour {colour!r}; expected one of: {', '.join(catalog.COLOURS)}",
                          _field("color"), json.dumps(colour)) from None
    try:
        shape = check_shape(shape) if shape is not None else None
    except (UserError, AttributeError):
        raise where.error(f"{label}: unknown shape {shape!r}; expected one of: {', '.join(catalog.SHAPES)}",
                          _field("shape"), json.dumps(shape)) from None
    if size is not None and (not isinstance(size, str) or size not in catalog.SIZES):
        raise where.error(f"{label}: unknown size {size!r}; expected one of: {', '.join(catalog.SIZES)}",
                          _field("size"))
    return ObjectSpec(shape=shape, colour=colour, size=size)


def _visual_objects(description: dict[str, Any] | None, where: _Where) -> list[ObjectSpec]:
    if description is None:
        return [ObjectSpec()]
    if "objects" in description:
        objects = _objects(description["objects"], description, where)
        if not objects:
            raise where.error("'description.objects' is empty", _field("objects"))
        return objects
    return [_object(description, where, "'description'")]


def _objects(raw: Any, description: dict[str, Any], where: _Where) -> list[ObjectSpec]:
    """`[{...}, {...}]` or `["<obj1>", "<obj2>"]` with the placeholders defined in the description."""
    if not isinstance(raw, list):
        raise where.error("'description.objects' must be a list of objects", _field("description"))
    out = []
    for i, item in enumerate(raw):
        label = f"description.objects[{i + 1}]"
        if isinstance(item, str):
            if item not in description:
                raise where.error(f"{label}: placeholder {item!r} is not defined in the description",
                                  json.dumps(item))
            out.append(_object(description[item], where, f"description.{item}"))
        else:
            out.append(_object(item, where, label))
    return out


def _relation(raw: Any, where: _Where) -> str:
    if not isinstance(raw, str):
        raise where.error(f"'description.relation' must be one of: {', '.join(relations.known())} "
                          "(or the original spellings left-of, right-of, front-of, behind)", _field("relation"))
    found = relations.find(raw)
    if found is None:
        raise where.error(f"unknown relation {raw!r}; expected one of: {', '.join(relations.known())}",
                          _field("relation"), json.dumps(raw))
    return found


def _action(description: dict[str, Any], where: _Where) -> ActionSpec:
    for key in description:
        if key.startswith("<") or key in ("objects", "relation", "relations", "action", "trace-actions",
                                          *IGNORED_DESCRIPTION_KEYS):
            continue
        raise where.error(f"description: unknown field {key!r}; expected objects, relations, action, "
                          "trace-actions", _field(key))
    rel = description.get("relation")
    rels = description.get("relations")
    if rel is None and isinstance(rels, list) and rels:
        rel = rels[0]
    verb = description.get("action", "move")
    if not isinstance(verb, str):
        raise where.error("'description.action' must be a string like \"move\"", _field("action"))
    if rel is None:
        # "move-right-of" carries its relation
        try:
            return parse_action(verb)
        except UserError:
            raise where.error("an action-word lesson needs 'description.relations' (e.g. [\"right-of\"])",
                              _field("description")) from None
    relation = _relation(rel, where)
    verb_word = verb.replace("-", " ").replace("_", " ").split()[0] if verb.strip() else "move"
    try:
        return parse_action(f"{verb_word} {relation}")
    except UserError as exc:
        raise where.error(exc.message, _field("action")) from None


def _trace(description: dict[str, Any], action: ActionSpec, where: _Where) -> list[Step]:
    """`trace-actions` -> steps (0-based object indices); the trainer's own demo if absent."""
    trace = description.get("trace-actions")
    if trace is None:
        return [Step("pick_up", 0), Step("place", 0, relation=action.relation, ref=1)]
    names = description.get("objects", [])
    if not isinstance(trace, list):
        raise where.error("'trace-actions' must be a list of actions", _field("trace-actions"))

    def index(arg: Any, label: str) -> int:
        if isinstance(arg, str) and arg in names:
            return names.index(arg)
        raise where.error(f"trace-actions: {label} {arg!r} is not one of the description's objects "
                          f"({', '.join(map(str, names))})", _field("trace-actions"))

    steps = []
    for item in trace:
        if not isinstance(item, dict) or not isinstance(item.get("name"), str):
            raise where.error("trace-actions: each action needs a \"name\" (pick-up, place, point)",
                              _field("trace-actions"))
        name = item["name"].replace("-", "_")
        if name in ("pick_up", "pickup", "point"):
            name = "point" if name == "point" else "pick_up"
            steps.append(Step(name, index(item.get("argument", item.get("argument1")), "argument")))
        elif name == "place":
            obj = index(item.get("argument1", item.get("argument")), "argument1")
            ref = index(item.get("argument2"), "argument2")
            steps.append(Step("place", obj, relation=_relation(item.get("relation", action.relation), where),
                              ref=ref))
        else:
            raise where.error(f"trace-actions: unknown action {item['name']!r}; expected pick-up, place, point",
                              _field("trace-actions"), json.dumps(item["name"]))
    return steps
