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

A given `content` is held to the description (`legacy_content`): what the description leaves
open is laid out as the sentence says it, and an inform or react that says other than its
description lays out is refused. A script's own `trace-actions` that do not reach the action's
goal skip their lesson with the reason (`legacy_trace`): they show nothing to learn from.

Errors name the file, the line where the lesson (or the field) starts, and the 1-based lesson
number: `script.json:14: lesson 3: 'signal' must be one of inform, verify, react, generate`.
Every list of valid names in an error is read from the declarations (`aileen.domain`: the
channels, relations, actions and composites), never written here. A lesson's `description`
is read by `legacy_description`; where each value stands in the text, by `legacy_where`.
"""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path
from typing import Any

from aileen.curriculum import legacy_content, legacy_scene, legacy_trace, placeholders
from aileen.curriculum.legacy_description import (
    COMPOSITE_KEYS,
    IGNORED_DESCRIPTION_KEYS,
    IGNORED_OBJECT_KEYS,
    read_action,
    read_composite,
    read_objects,
    read_relation,
    read_trace,
    read_visual_objects,
)
from aileen.curriculum.legacy_where import Where as _Where
from aileen.curriculum.legacy_where import field as _field
from aileen.curriculum.legacy_where import spans as _spans
from aileen.curriculum.lesson import (
    EMPTY_LESSON,
    SIGNALS,
    ActionSpec,
    Curriculum,
    Lesson,
    ObjectSpec,
    Step,
    auto_demonstration,
    check_lesson,
    most_distractors,
    read_lesson_text,
    said_of_unread,
)
from aileen.curriculum.sentences import action_from_content
from aileen.domain import channels
from aileen.errors import UserError
from aileen.strictjson import duplicate_key_line, no_duplicates

LESSON_TYPES: tuple[str, ...] = ("visual-word", "spatial-word", "action-word", "composite-word")
LESSON_KEYS: tuple[str, ...] = ("lesson-type", "content", "description", "signal", "distractors",
                                "is_positive", "comment", "concept")
# Webots-only fields the original's scripts write beside a lesson's own: ignored (the trainer
# lays scenes out with its own definitions), as inside a description.
IGNORED_LESSON_KEYS: tuple[str, ...] = (*IGNORED_OBJECT_KEYS, *IGNORED_DESCRIPTION_KEYS)
# a lesson's object keys sit beside its own ({"description": "box", "color": "red", "signal": ...})
channels.reserve_keys("the original JSON lesson format", (*LESSON_KEYS, *IGNORED_LESSON_KEYS, *COMPOSITE_KEYS))


def loads(text: str, path: str = "<string>") -> Curriculum:
    """Parse an original-format script; every error is a `UserError` naming the lesson and field."""
    try:
        data = json.loads(text, object_pairs_hook=no_duplicates)
    except json.JSONDecodeError as exc:
        raise UserError(f"invalid JSON: {exc.msg} (column {exc.colno})", path=path, line=exc.lineno) from None
    except RecursionError:
        raise UserError("nested too deeply to be a lesson script", path=path) from None
    except ValueError as exc:  # a duplicate key: one of the two values would be dropped unseen
        raise UserError(f"invalid lesson script: {exc}", path=path, line=duplicate_key_line(text)) from None
    others: list[ObjectSpec] = []  # a saved scene's objects beside its lesson's
    if legacy_scene.is_scene(data):  # a scene the original's instructor saved: one lesson
        scene_lesson, others = legacy_scene.lesson_of(data, path, text)
        data = [scene_lesson]
    if not isinstance(data, list):
        raise UserError("expected a JSON list of lessons ([{...}, ...]), or a saved scene "
                        "({\"interaction\": {...}, \"scene\": [...]})", path=path, line=1)
    if not data:
        raise UserError("no lessons; expected a JSON list with at least one lesson", path=path, line=1)
    spans = _spans(text)
    lessons = []
    for i, raw in enumerate(data):
        where = _Where(text, path, i, spans[i] if i < len(spans) else None)
        lesson = _lesson(_unflatten(raw, where), where)
        if others:
            lesson = dataclasses.replace(lesson, objects=[*lesson.objects, *others])
        lessons.append(_checked_trace(lesson, seed=i))
    return Curriculum(lessons=said_of_unread(lessons), seed=0, title=Path(path).stem, path=path)


def load(path: str | Path) -> Curriculum:
    """Read an original AILEEN `.json` lesson script."""
    return loads(read_lesson_text(path), str(path))


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


def _lesson(raw: Any, where: _Where) -> Lesson:
    if not isinstance(raw, dict):
        raise where.error("expected an object with 'lesson-type', 'content', 'description', 'signal'")
    if not raw:  # a stub the original's repository keeps (`comparative-large` at 8eef4cf is `[{}]`)
        return Lesson(signal="inform", content="", source=where.source, skip=EMPTY_LESSON)
    for key in raw:
        if key not in (*LESSON_KEYS, *IGNORED_LESSON_KEYS):
            raise where.error(f"unknown field {key!r}; expected one of: {', '.join(LESSON_KEYS)}", _field(key))
    # any letter case, as its colours, shapes and "is_positive" are read ("Inform" was refused
    # where "Red" and "True" were taken)
    kind = _folded(raw.get("lesson-type"))
    if kind not in LESSON_TYPES:
        if "lesson-type" not in raw:
            raise where.error(f"missing 'lesson-type'; expected one of {', '.join(LESSON_TYPES)}")
        raise where.error(f"'lesson-type' must be one of {', '.join(LESSON_TYPES)} (got {kind!r})",
                          _field("lesson-type"))
    signal = _folded(raw.get("signal"))
    if signal not in SIGNALS:
        if "signal" not in raw:
            raise where.error(f"missing 'signal'; expected one of {', '.join(SIGNALS)}")
        raise where.error(f"'signal' must be one of {', '.join(SIGNALS)} (got {signal!r})", _field("signal"))
    distractors = _distractors(raw.get("distractors"), where)
    expect = None
    if "is_positive" in raw:
        value = str(raw["is_positive"]).strip().lower()
        if value not in ("true", "false"):
            raise where.error("'is_positive' must be \"True\" or \"False\" (any letter case) or true/false",
                              _field("is_positive"))
        expect = "success" if value == "true" else "failure"
        if expect == "failure" and signal in ("inform", "react"):
            raise where.error(f"'is_positive' false on a{'n' if signal == 'inform' else ''} {signal} lesson: "
                              f"{_UNGRADED[signal]}; a false exam is a verify", _field("is_positive"))
    content = raw.get("content")
    if content is not None and (not isinstance(content, str) or not content.strip()):
        raise where.error(f"'content' must be a non-empty string, found {json.dumps(content)[:40]}", _field("content"))
    if content is not None and signal != "generate" and not any(ch.isalnum() for ch in content):
        raise where.error(f"'content' {content!r} says no word: give what the trainer says", _field("content"))
    note = raw.get("comment", "")
    if not isinstance(note, str):
        raise where.error(f"'comment' must be a string, found {json.dumps(note)[:40]}", _field("comment"))
    concept = raw.get("concept")
    if concept is not None and (not isinstance(concept, str) or not concept.strip()):
        raise where.error("'concept' must be a non-empty string (the original's generate lessons say \"object\"), "
                          f"found {json.dumps(concept)[:40]}", _field("concept"))
    description = raw.get("description")
    if description is not None and not isinstance(description, dict):
        raise where.error("'description' must be an object", _field("description"))

    relation: str | None = None
    name_objects = False
    action: ActionSpec | None = None
    demonstration: list[Step] | None = None
    composite: str | None = None
    if kind == "visual-word":
        objects = read_visual_objects(description, where)
        said = placeholders.sentence("visual", objects)
    elif kind == "spatial-word":
        if description is None:
            raise where.error("a spatial-word lesson needs 'description' with 'objects' and 'relation'")
        # The original's lesson generator names only the relation: its instructor drew the
        # two objects at random, as for `<obj1>` placeholders (named below: `name_objects`).
        objects = ([ObjectSpec(), ObjectSpec()] if "objects" not in description
                   else read_objects(description["objects"], description, where))
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
            relation = read_relation(description.get("relation"), where)
            said = placeholders.sentence("spatial", objects, relation)
    elif kind == "composite-word":
        composite, objects = read_composite(description, where)
        said = composite
    else:
        if description is None:
            raise where.error("an action-word lesson needs 'description' with 'objects' and 'relations'")
        objects = read_objects(description.get("objects"), description, where)
        action = read_action(description, where)
        if len(objects) != action.n_objects:
            what = ("two objects: the one moved, then the reference" if action.n_objects == 2
                    else "one object: the one acted on")
            raise where.error(f"'description.objects' must list {what} for the action {action.name!r}",
                              _field("description"), _field("objects"))
        said = placeholders.sentence("action", objects, action=action)
        if signal != "react":
            demonstration = read_trace(description, action, where)
        elif content is not None:
            # A react lesson's task is what the trainer says: where the script's action is not
            # its sentence's ("move-left-of" with "move ... right of ..."), the sentence is laid
            # out for and graded, and the transcript says so.
            told = action_from_content(content)
            if told is not None and told != action:
                note = "; ".join(n for n in (note, f"the script's action {action.name!r} is not its sentence's "
                                             f"{told.name!r}: the sentence is the task") if n)
                action = told
    say_false = False
    if content is not None and placeholders.PLACEHOLDER.search(content):
        # "move <obj1> near <obj2>": the sentence is a template over the description's objects;
        # those it describes are said now, those the trainer draws once drawn
        # (`placeholders.name`), and the sentence is held to the description as any is
        content = _template(content, description, objects, where)
        name_objects = signal != "generate" and placeholders.TEMPLATE.search(content) is not None
    if content is not None and signal != "generate" and composite is None:
        objects = _held_to_content(objects, relation, action, content, signal, expect, where)
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
    if signal == "react" and action is None:
        # as our TOML files' reader refuses it: the agent was asked for nothing to do
        raise where.error(f"a react lesson needs an action: a {kind} lesson names none; an action-word lesson "
                          "with 'action' and 'relations' (\"move <obj1> left of <obj2>\")", _field("signal"))
    if signal == "generate" and not objects:
        raise where.error("a generate lesson needs something on the table to describe: give 'description'")
    lesson = Lesson(signal=signal, content=" ".join(content.split()), objects=objects, relation=relation,
                    distractors=distractors, demonstration=demonstration, source=where.source, action=action,
                    expect=None if signal == "generate" else expect, note=note, composite=composite,
                    say_false=say_false, concept=concept, name_objects=name_objects)
    check_lesson(lesson)
    return lesson


_UNGRADED = {"inform": "an inform teaches what it says, true of the table it lays out",
             "react": "a react is graded by whether its goal is reached"}


def _folded(value: object) -> object:
    """A text value in lower case with its ends trimmed; anything else as it is (refused later)."""
    return value.strip().lower() if isinstance(value, str) else value


def _distractors(raw: Any, where: _Where) -> int:
    """`distractors` as a count. JSON has one kind of number, so `2`, `2.0` and `1e2` are all
    whole numbers (more than fit are laid out as many as fit, and the transcript says so) up to
    what the table could hold (`lesson.most_distractors`); `1.5`, `-1`, `true`, `"two"`, an
    infinity and `1e20` are not."""
    if raw is None:
        return 0
    if isinstance(raw, float) and raw.is_integer():
        raw = int(raw)
    if not isinstance(raw, int) or isinstance(raw, bool) or raw < 0:
        raise where.error(f"'distractors' must be a whole number >= 0, found {json.dumps(raw)[:40]}", _field("distractors"))
    if raw > most_distractors():
        raise where.error(f"'distractors' must be at most {most_distractors()} (the table holds no more of the "
                          f"smallest objects side by side), found {json.dumps(raw)[:40]}", _field("distractors"))
    return raw


def _held_to_content(objects: list[ObjectSpec], relation: str | None, action: ActionSpec | None, content: str,
                     signal: str, expect: str | None, where: _Where) -> list[ObjectSpec]:
    """The objects as the sentence says them where the description leaves them open (the
    trainer lays out what it says; not for an exam whose answer is a failure, whose sentence
    is false of the table on purpose). An inform or a react whose sentence contradicts its
    description (colour, shape, size, relation, verb) is refused: the agent would learn from,
    or be asked about, a table that is not what is said. A verify may contradict it: that is
    a false exam, graded against the table."""
    if signal in ("inform", "react"):
        # a react's action is its sentence's already (see above): only its objects are held to it
        problem = legacy_content.contradiction(objects, relation, action if signal == "inform" else None, content)
        if problem is not None:
            raise where.error(f"{problem}: {'an inform' if signal == 'inform' else 'a react'} must say what its "
                              "description lays out",
                              _field("content"))
    if expect == "failure":
        return objects
    return legacy_content.fill(objects, relation, action, content)


def _checked_trace(lesson: Lesson, *, seed: int) -> Lesson:
    """The lesson, skipped with the reason when its `trace-actions` do not reach its action's
    goal (`legacy_trace`); only a script's own trace is checked, the trainer's shows its verb."""
    if (lesson.signal != "inform" or lesson.demonstration is None or lesson.action is None
            or lesson.skip is not None or lesson.demonstration == auto_demonstration(lesson.action)):
        return lesson  # a verify's demonstration is an exam: one that misses the goal is graded "no"
    why = legacy_trace.shortfall(lesson, seed=seed)
    return lesson if why is None else dataclasses.replace(lesson, skip=why)


def _template(content: str, description: dict[str, Any] | None, objects: list[ObjectSpec], where: _Where) -> str:
    """The sentence with each of its placeholders ("<obj1>") said as the description gives its
    object, or, for an object the trainer draws, written `<objN>` by its place in `objects`
    (`placeholders.name` says it once drawn). A placeholder `objects` does not list is an error."""
    listed = (description or {}).get("objects")
    names = [o for o in listed if isinstance(o, str)] if isinstance(listed, list) else []

    def said(m: re.Match[str]) -> str:
        if not isinstance(listed, list) or m.group(0) not in listed:
            raise where.error(f"'content' names {m.group(0)!r}, which 'description.objects' does not list"
                              + (f" ({', '.join(names)})" if names else ""), _field("content"))
        i = listed.index(m.group(0))
        spec = objects[i]
        return spec.describe() if channels.kind_of(spec.appearance) is not None else f"<obj{i + 1}>"

    return placeholders.PLACEHOLDER.sub(said, content)
