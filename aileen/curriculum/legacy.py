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
`is_positive: "False"` (any letter case, or a JSON boolean) marks an exam whose right answer
is a failure; without `content` the trainer then says something false about the scene it lays
out (`curriculum.falsehood`). The original's spellings are accepted: `color`, every relation
the domain declares (`left-of`, `left-of-ec`, `behind2`, `behind-disjunctive`, `distant`,
`next-to`, `on`, `larger-than`, ...), shape `cube`, action descriptions with `<obj1>`
placeholders (one the description does not define is a random object, as the original drew
it) and `trace-actions` (every primitive action the domain declares: `pick-up`, `place`,
`point`, `push`); `composite-word` lessons; the signal `generate` with its `concept`. Webots-only fields
(`rgb`, `position` in Webots' frame, `initial_configuration`, `language`) are ignored: the
trainer lays scenes out with its own definitions.

Errors name the file, the line where the lesson (or the field) starts, and the 1-based lesson
number: `script.json:14: lesson 3: 'signal' must be one of inform, verify, react, generate`.
Every list of valid names in an error is read from the declarations (`aileen.domain`: the
channels, relations, actions and composites), never written here.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from aileen.curriculum import placeholders
from aileen.curriculum.lesson import (
    SIGNALS,
    ActionSpec,
    Curriculum,
    Lesson,
    ObjectSpec,
    Source,
    Step,
    auto_demonstration,
    check_lesson,
    read_lesson_text,
)
from aileen.curriculum.sentences import parse_action
from aileen.domain import actions, channels, composites, relations
from aileen.errors import UserError
from aileen.strictjson import no_duplicates

LESSON_TYPES: tuple[str, ...] = ("visual-word", "spatial-word", "action-word", "composite-word")
LESSON_KEYS: tuple[str, ...] = ("lesson-type", "content", "description", "signal", "distractors",
                                "is_positive", "comment", "concept")
COMPOSITE_KEYS: tuple[str, ...] = ("composite", "objects")
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


def loads(text: str, path: str = "<string>") -> Curriculum:
    """Parse an original-format script; every error is a `UserError` naming the lesson and field."""
    try:
        data = json.loads(text, object_pairs_hook=no_duplicates)
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
        lessons.append(_lesson(_unflatten(raw, where), where))
    return Curriculum(lessons=lessons, seed=0, title=Path(path).stem, path=path)


def load(path: str | Path) -> Curriculum:
    """Read an original AILEEN `.json` lesson script."""
    return loads(read_lesson_text(path), str(path))


def _field(name: str) -> str:
    return f'"{name}"'


def _unflatten(raw: Any, where: _Where) -> Any:
    """The original's first, flat form of a visual lesson in the later one: `{"lesson": "visual",
    "description": "box", "color": "red", "shape": "box", "signal": "inform"}` (the sentence in
    `description`, the object's fields beside it) is `{"lesson-type": "visual-word", "content":
    "box", "description": {"color": "red", "shape": "box"}, ...}`. Anything else as it is."""
    if not isinstance(raw, dict) or "lesson" not in raw or "lesson-type" in raw:
        return raw
    if raw["lesson"] != "visual":
        raise where.error(f"'lesson' (the first form of a lesson) must be \"visual\" (got {raw['lesson']!r}); "
                          f"later scripts say 'lesson-type': one of {', '.join(LESSON_TYPES)}", _field("lesson"))
    if "content" in raw:
        raise where.error("a lesson of the first form says its sentence in 'description', not 'content'",
                          _field("content"))
    out: dict[str, Any] = {"lesson-type": "visual-word"}
    if "description" in raw:
        out["content"] = raw["description"]
    described = {k: v for k, v in raw.items() if k not in LESSON_KEYS and k != "lesson"}
    out.update((k, v) for k, v in raw.items() if k in LESSON_KEYS and k != "description")
    out["description"] = described
    return out


EMPTY_LESSON = "an empty lesson ({}): nothing to lay out or say"


def _lesson(raw: Any, where: _Where) -> Lesson:
    if not isinstance(raw, dict):
        raise where.error("expected an object with 'lesson-type', 'content', 'description', 'signal'")
    if not raw:  # a stub the original's repository keeps (`comparative-large` at 8eef4cf is `[{}]`)
        return Lesson(signal="inform", content="", source=where.source, skip=EMPTY_LESSON)
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
            raise where.error("'is_positive' must be \"True\" or \"False\" (any letter case) or true/false",
                              _field("is_positive"))
        expect = "success" if value == "true" else "failure"
    content = raw.get("content")
    if content is not None and (not isinstance(content, str) or not content.strip()):
        raise where.error("'content' must be a non-empty string", _field("content"))
    note = raw.get("comment", "")
    if not isinstance(note, str):
        raise where.error("'comment' must be a string", _field("comment"))
    concept = raw.get("concept")
    if concept is not None and (not isinstance(concept, str) or not concept.strip()):
        raise where.error("'concept' must be a non-empty string (the original's generate lessons say \"object\")",
                          _field("concept"))
    description = raw.get("description")
    if description is not None and not isinstance(description, dict):
        raise where.error("'description' must be an object", _field("description"))

    relation: str | None = None
    action: ActionSpec | None = None
    demonstration: list[Step] | None = None
    composite: str | None = None
    if kind == "visual-word":
        objects = _visual_objects(description, where)
        said = placeholders.sentence("visual", objects)
    elif kind == "spatial-word":
        if description is None:
            raise where.error("a spatial-word lesson needs 'description' with 'objects' and 'relation'")
        # The original's lesson generator names only the relation: its instructor drew the
        # two objects at random, as for `<obj1>` placeholders (named below: `name_objects`).
        objects = ([ObjectSpec(), ObjectSpec()] if "objects" not in description
                   else _objects(description["objects"], description, where))
        rel_word = description.get("relation")
        valued = channels.read_value(rel_word.strip().lower(), {}) if isinstance(rel_word, str) else None
        if len(objects) == 1 and valued is not None:
            # an early script's one object "related" by a value of a channel ("small"): a visual
            # lesson about that object at that value, as the script's authors later wrote it
            kind = "visual-word"
            objects = [ObjectSpec(appearance={**objects[0].appearance, valued[0]: valued[1]},
                                  position=objects[0].position)]
            said = placeholders.sentence("visual", objects)
        elif len(objects) != 2:
            raise where.error("'description.objects' must list two objects for a spatial-word lesson",
                              _field("description"), _field("objects"))
        else:
            relation = _relation(description.get("relation"), where)
            said = placeholders.sentence("spatial", objects, relation)
    elif kind == "composite-word":
        composite, objects = _composite(description, where)
        said = composite
    else:
        if description is None:
            raise where.error("an action-word lesson needs 'description' with 'objects' and 'relations'")
        objects = _objects(description.get("objects"), description, where)
        action = _action(description, where)
        if len(objects) != action.n_objects:
            what = ("two objects: the one moved, then the reference" if action.n_objects == 2
                    else "one object: the one acted on")
            raise where.error(f"'description.objects' must list {what} for the action {action.name!r}",
                              _field("description"), _field("objects"))
        said = placeholders.sentence("action", objects, action=action)
        if signal != "react":
            demonstration = _trace(description, action, where)
    say_false = False
    name_objects = False
    if content is None:
        if expect == "failure" and signal != "generate":
            if kind == "composite-word":
                raise where.error(f"a {kind} lesson with 'is_positive' false needs 'content': the trainer "
                                  "makes up false sentences about objects, their relations and actions")
            say_false = True  # the trainer makes the false sentence when it lays the scene out
        if signal == "generate":
            said = ""  # the agent does the saying (as in our TOML files)
        elif say_false:
            said = said or objects[0].describe()  # a random object: the sentence is made up at layout
        elif composite is None and placeholders.open_objects(objects):
            # `<obj1>` placeholders (or objects without colour or shape): the trainer draws them
            # and says what it drew, as the original did (`placeholders.name`)
            name_objects = True
            said = said or objects[0].describe()
        content = said
    if signal == "generate" and not objects:
        raise where.error("a generate lesson needs something on the table to describe: give 'description'")
    lesson = Lesson(signal=signal, content=" ".join(content.split()), objects=objects, relation=relation,
                    distractors=distractors, demonstration=demonstration, source=where.source, action=action,
                    expect=None if signal == "generate" else expect, note=note, composite=composite,
                    say_false=say_false, concept=concept, name_objects=name_objects)
    check_lesson(lesson)
    return lesson


def _composite(description: dict[str, Any] | None, where: _Where) -> tuple[str, list[ObjectSpec]]:
    """`{"composite": "wall"}`, optionally with `objects` (its parts; default: the parts the
    word declares)."""
    if description is None or "composite" not in description:
        raise where.error(f"a composite-word lesson needs 'description.composite', one of: "
                          f"{', '.join(composites.COMPOSITES)}", _field("description"))
    for key in description:
        if key not in (*COMPOSITE_KEYS, *IGNORED_DESCRIPTION_KEYS) and not _is_placeholder(key):
            raise where.error(f"description: unknown field {key!r}; expected one of: {', '.join(COMPOSITE_KEYS)}",
                              _field(key))
    word = description["composite"]
    if not isinstance(word, str):
        raise where.error(f"'description.composite' must be one of: {', '.join(composites.COMPOSITES)}",
                          _field("composite"))
    try:
        comp = composites.get(word)
    except UserError as exc:
        raise where.error(exc.message, _field("composite")) from None
    if "objects" not in description:
        return comp.word, [ObjectSpec(shape) for shape in comp.parts]
    objects = _objects(description["objects"], description, where)
    if len(objects) != len(comp.parts):
        raise where.error(f"a {comp.word} has {len(comp.parts)} parts; 'description.objects' lists "
                          f"{len(objects)}", _field("description"), _field("objects"))
    for i, (spec, shape) in enumerate(zip(objects, comp.parts)):
        if shape is not None and spec.shape not in (None, shape):
            raise where.error(f"description.objects[{i + 1}]: part {i + 1} of a {comp.word} is a {shape}, "
                              f"not a {spec.shape}", _field("objects"))
    return comp.word, [spec.with_values(shape=spec.shape or shape) for spec, shape in zip(objects, comp.parts)]


def _is_placeholder(name: str) -> bool:
    return len(name) > 2 and name.startswith("<") and name.endswith(">")


def _object(raw: Any, where: _Where, label: str) -> ObjectSpec:
    if not isinstance(raw, dict):
        raise where.error(f"{label} must be an object like {{\"color\": \"red\", \"shape\": \"box\"}}",
                          _field("description"))
    names = sorted((*c.keys, c.name)[0] for c in channels.CHANNELS)  # the original's spellings: color, shape, size
    for key in raw:
        if key not in (*channels.key_names(), *IGNORED_OBJECT_KEYS):
            raise where.error(f"{label}: unknown field {key!r}; expected {', '.join(names)}", _field(key))
    values: dict[str, str] = {}
    for channel in channels.CHANNELS:
        key = next((k for k in (*channel.keys, channel.name) if k in raw), None)  # "color" before "colour"
        if key is None or raw[key] is None:
            continue
        try:
            values[channel.name] = channel.check(raw[key])
        except UserError:
            raise where.error(f"{label}: unknown {channel.name} {raw[key]!r}; expected one of: "
                              f"{', '.join(channel.values)}", _field(key), json.dumps(raw[key])) from None
    return ObjectSpec(appearance=values)


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
            if item in description:
                out.append(_object(description[item], where, f"description.{item}"))
            elif _is_placeholder(item):
                out.append(ObjectSpec())  # not described: the trainer draws a random object, as the original did
            else:
                raise where.error(f"{label}: {item!r} is neither an object nor a placeholder like \"<obj1>\"",
                                  json.dumps(item))
        else:
            out.append(_object(item, where, label))
    return out


def _relation(raw: Any, where: _Where) -> str:
    if not isinstance(raw, str):
        raise where.error(f"'description.relation' must be one of: {', '.join(relations.known())} "
                          "(spelt with spaces, hyphens or underscores)", _field("relation"))
    found = relations.find(raw)
    if found is None:
        raise where.error(f"unknown relation {raw!r}; expected one of: {', '.join(relations.known())}",
                          _field("relation"), json.dumps(raw))
    return found


def _action(description: dict[str, Any], where: _Where) -> ActionSpec:
    for key in description:
        if _is_placeholder(key) or key in ("objects", "relation", "relations", "action", "trace-actions",
                                           *IGNORED_DESCRIPTION_KEYS):
            continue
        raise where.error(f"description: unknown field {key!r}; expected objects, relations, action, "
                          "trace-actions", _field(key))
    rel = description.get("relation")
    rels = description.get("relations")
    if rels is not None and not isinstance(rels, list):
        raise where.error("'description.relations' must be a list like [\"right-of\"] (or [] for push)",
                          _field("relations"))
    if rel is None and rels:
        rel = rels[0]
    verb = description.get("action", "move")
    if not isinstance(verb, str) or not verb.strip():
        raise where.error(f"'description.action' must be one of: {', '.join(actions.VERBS)}", _field("action"))
    words = verb.replace("-", " ").replace("_", " ").split()
    declared = actions.find_verb(words[0])
    if declared is None:
        raise where.error(f"unknown action {verb!r}; expected one of: {', '.join(actions.VERBS)} "
                          "(\"move\" with 'relations', or \"move-right-of\")", _field("action"), json.dumps(verb))
    try:
        if rel is None or not declared.takes_relation:
            # "move-right-of" carries its relation; "push" takes none
            return parse_action(verb)
        return parse_action(f"{declared.name} {_relation(rel, where)}")
    except UserError as exc:
        raise where.error(exc.message, _field("action")) from None


def _trace(description: dict[str, Any], action: ActionSpec, where: _Where) -> list[Step]:
    """`trace-actions` -> steps (0-based object indices); the trainer's own demo if absent."""
    trace = description.get("trace-actions")
    if trace is None:
        return auto_demonstration(action)
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
            raise where.error(f"trace-actions: each action needs a \"name\", one of: {', '.join(actions.ACTIONS)}",
                              _field("trace-actions"))
        try:
            act = actions.action(item["name"])
        except UserError as exc:
            raise where.error(f"trace-actions: {exc.message}", _field("trace-actions"),
                              json.dumps(item["name"])) from None
        if act.touches:
            steps.append(Step(act.name, index(item.get("argument", item.get("argument1")), "argument")))
        else:
            obj = index(item.get("argument1", item.get("argument")), "argument1")
            ref = index(item.get("argument2"), "argument2")
            if ref == obj:
                raise where.error("trace-actions: place puts an object relative to itself", _field("trace-actions"))
            rel = item.get("relation", action.relation)
            if rel is None:
                raise where.error("trace-actions: place needs a \"relation\"", _field("trace-actions"))
            steps.append(Step(act.name, obj, relation=_relation(rel, where), ref=ref))
    return steps
