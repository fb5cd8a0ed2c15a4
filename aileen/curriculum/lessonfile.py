"""Our hand-written lesson format (TOML), read with `file:line` errors.

```toml
title = "colours first"
seed = 1

[[lesson]]
signal = "inform"
content = "red box"
objects = ["red box"]

[[lesson]]
signal = "inform"
content = "move the red box right of the blue cone"
objects = ["red box", "blue cone"]
demonstration = "auto"
```

The full format is in docs/lessons.md. `tomllib` reports lines for syntax errors only, so
semantic errors are located here: by the n-th `[[lesson]]` header, the key's line inside its
block, and where possible the line holding the offending value. Unknown keys are errors, so
a typo cannot pass silently.
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

from aileen.curriculum.lesson import (
    EXPECTS,
    SIGNALS,
    ActionSpec,
    Curriculum,
    Lesson,
    ObjectSpec,
    Source,
    Step,
    auto_demonstration,
    check_lesson,
    parse_step,
    read_lesson_text,
    said_of_unread,
)
from aileen.curriculum import legacy_content
from aileen.curriculum.sentences import action_from_content, parse_action, parse_object, read_content
from aileen.domain import actions, channels, composites, relations
from aileen.errors import UserError

# The trainer's verdict each signal can carry (`feedback = ...`; agent/feedback.py).
FEEDBACK: dict[str, str] = {"verify": "wrong", "react": "confirm"}
TOP_KEYS: dict[str, str] = {
    "title": "a string",
    "description": "a string",
    "seed": "a whole number >= 0",
    "after": "a list of lesson files (beside this one) whose words it takes as known",
    "lesson": "[[lesson]] tables",
}
T = TypeVar("T")

LESSON_KEYS: dict[str, str] = {
    "signal": f"one of {', '.join(SIGNALS)}",
    "content": "a string: what the trainer says (a generate lesson may leave it out)",
    "objects": "a list of objects: strings like 'red box' or tables {shape, colour, size, position}",
    "relation": f"one of {', '.join(relations.known())}",
    "distractors": "a whole number >= 0",
    "demonstration": "'auto' or a list of steps like 'pick_up 1', 'place 1 right of 2'",
    "action": "an action like 'move right of' or 'push'",
    "composite": "a composite word, e.g. 'wall': its parts are laid out as the word says (objects default to its parts)",
    "near_miss": "true or false: lay the relation out as a near miss (close to it, but not it)",
    "expect": f"one of {', '.join(EXPECTS)}",
    "feedback": "'wrong' (verify) or 'confirm' (react)",
    "seed": "a whole number >= 0",
    "note": "a string",
    "as_said": "a list of words the trainer means as said (a new word one letter from a known one, 'rox' beside 'box')",
}


# The key of an object table beside its channels' (where it stands)
POSITION = "position"
channels.reserve_keys("a TOML lesson file", (*LESSON_KEYS, POSITION))


def object_keys() -> tuple[str, ...]:
    """The keys of an object table: every channel's name (and its other keys, "color"), "position"."""
    return (*channels.key_names(), POSITION)


class _Locator:
    """Finds the lines of lessons, keys and values in the TOML text."""

    _HEADER = re.compile(r"^\s*\[\[\s*lesson\s*\]\]")
    _ANY_HEADER = re.compile(r"^\s*\[")

    def __init__(self, text: str) -> None:
        self.lines = text.splitlines()
        self.headers = [i for i, line in enumerate(self.lines) if self._HEADER.match(line)]
        self.first_table = next((i for i, line in enumerate(self.lines) if self._ANY_HEADER.match(line)),
                                len(self.lines))

    def _block(self, n: int) -> tuple[int, int] | None:
        if n >= len(self.headers):
            return None
        start = self.headers[n]
        end = next((i for i in range(start + 1, len(self.lines)) if self._ANY_HEADER.match(self.lines[i])),
                   len(self.lines))
        return start, end

    def lesson(self, n: int) -> int | None:
        """1-based line of the n-th (0-based) `[[lesson]]` header."""
        return self.headers[n] + 1 if n < len(self.headers) else None

    def key(self, n: int, key: str) -> int | None:
        """1-based line of `key = ...` inside lesson n; the header line if not found."""
        block = self._block(n)
        if block is None:
            return None
        pattern = re.compile(rf"^\s*(?:{re.escape(key)}|\"{re.escape(key)}\"|'{re.escape(key)}')\s*=")
        for i in range(block[0] + 1, block[1]):
            if pattern.match(self.lines[i]):
                return i + 1
        return block[0] + 1

    def value(self, n: int, key: str, needle: str) -> int | None:
        """1-based line of the first occurrence of `needle` from `key`'s line to the block end."""
        start = self.key(n, key)
        block = self._block(n)
        if start is None or block is None:
            return start
        for i in range(start - 1, block[1]):
            if needle in self.lines[i]:
                return i + 1
        return start

    def top(self, key: str) -> int | None:
        """1-based line of a top-level key or table header."""
        pattern = re.compile(rf"^\s*(?:\[+\s*)?(?:{re.escape(key)}|\"{re.escape(key)}\")\s*(?:=|\]|\.)")
        for i, line in enumerate(self.lines):
            if pattern.match(line):
                return i + 1
        return None


def _syntax_line(exc: tomllib.TOMLDecodeError) -> tuple[int | None, str]:
    lineno = getattr(exc, "lineno", None)
    msg = getattr(exc, "msg", None) or str(exc)
    m = re.search(r"\s*\(at line (\d+), column (\d+)\)$", msg)
    if m:
        lineno = lineno or int(m.group(1))
        msg = msg[: m.start()] + f" (column {m.group(2)})"
    elif "(at end of document)" in msg:
        msg = msg.replace(" (at end of document)", " (at end of file)")
    return lineno, msg


def loads(text: str, path: str = "<string>") -> Curriculum:
    """Parse lesson-file text; every error is a `UserError` naming `path:line`."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        line, msg = _syntax_line(exc)
        raise UserError(f"invalid TOML: {msg}", path=path, line=line) from None
    except RecursionError:  # tomllib recurses per nested array or inline table
        raise UserError("nested too deeply to be a lesson file", path=path) from None
    loc = _Locator(text)

    for key, value in data.items():
        if key not in TOP_KEYS:
            raise UserError(f"unknown key {key!r}; expected one of: {', '.join(TOP_KEYS)}",
                            path=path, line=loc.top(key))
    title = data.get("title", "")
    if not isinstance(title, str):
        raise UserError(f"'title' must be {TOP_KEYS['title']}", path=path, line=loc.top("title"))
    if not isinstance(data.get("description", ""), str):
        raise UserError(f"'description' must be {TOP_KEYS['description']}", path=path, line=loc.top("description"))
    seed = data.get("seed", 0)
    if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
        raise UserError(f"'seed' must be {TOP_KEYS['seed']}", path=path, line=loc.top("seed"))
    after = data.get("after", [])
    if not (isinstance(after, list) and all(isinstance(a, str) and a for a in after)):
        raise UserError(f"'after' must be {TOP_KEYS['after']}, e.g. after = [\"visual.toml\"]", path=path,
                        line=loc.top("after"))
    for a in after:  # (a file's own folder: a text read with no file names none)
        if Path(path).is_file() and not (Path(path).parent / a).is_file():
            raise UserError(f"'after': no lesson file {a!r} beside this one", path=path, line=loc.top("after"))
    raw_lessons = data.get("lesson", [])
    if not isinstance(raw_lessons, list) or not all(isinstance(x, dict) for x in raw_lessons):
        raise UserError("'lesson' must be [[lesson]] tables", path=path, line=loc.top("lesson"))
    if not raw_lessons:
        raise UserError("no lessons; expected at least one [[lesson]] table", path=path, line=None)
    lessons = [_lesson(raw, n, path, loc) for n, raw in enumerate(raw_lessons)]
    return Curriculum(lessons=said_of_unread(lessons), seed=seed, title=title, path=path, after=tuple(after))


def load(path: str | Path) -> Curriculum:
    """Read a `.toml` lesson file."""
    return loads(read_lesson_text(path), str(path))


def _lesson(raw: dict[str, Any], n: int, path: str, loc: _Locator) -> Lesson:
    source = Source(path, loc.lesson(n), n + 1,
                    tuple((key, line) for key in raw if (line := loc.key(n, key)) is not None))

    def fail(key: str, message: str, needle: str | None = None) -> UserError:
        line = loc.value(n, key, needle) if needle else loc.key(n, key)
        return source.error(message, line=line)

    def expect(key: str) -> UserError:
        return fail(key, f"{key!r} must be {LESSON_KEYS[key]}")

    def named(key: str, read: Callable[[str], T]) -> T | None:
        """The key's string value read by `read` (a declaration's lookup, whose UserError lists
        the valid names), located at the key; None when the key is absent."""
        value = raw.get(key)
        if value is None:
            return None
        if not isinstance(value, str):
            raise expect(key)
        try:
            return read(value)
        except UserError as exc:
            raise fail(key, exc.message) from None

    for key in raw:
        if key not in LESSON_KEYS:
            raise source.error(f"unknown key {key!r}; expected one of: {', '.join(LESSON_KEYS)}",
                               line=loc.key(n, key))
    if "signal" not in raw:
        raise source.error(f"missing 'signal': {LESSON_KEYS['signal']}")
    signal = raw["signal"]
    if not isinstance(signal, str) or signal not in SIGNALS:
        raise fail("signal", f"'signal' must be one of {', '.join(SIGNALS)} (got {signal!r})")
    if "content" not in raw and signal != "generate":
        raise source.error(f"missing 'content': {LESSON_KEYS['content']}")
    content = raw.get("content", "")
    if not isinstance(content, str):
        raise expect("content")
    if not content.strip() and signal != "generate":
        raise fail("content", "'content' is empty: give what the trainer says (only a generate lesson may leave it out)")
    content = " ".join(content.split())

    objects_raw = raw.get("objects", [])
    if not isinstance(objects_raw, list):
        raise expect("objects")
    objects = [_object(item, i, n, loc, source) for i, item in enumerate(objects_raw)]

    relation = named("relation", relations.canonical)

    distractors = raw.get("distractors", 0)
    if not isinstance(distractors, int) or isinstance(distractors, bool) or distractors < 0:
        raise expect("distractors")

    action = named("action", parse_action)
    if action is None and (signal == "react" or raw.get("demonstration") == "auto"):
        action = action_from_content(content)

    demonstration = _demonstration(raw, action, len(objects), n, loc, source) if "demonstration" in raw else None
    if demonstration is not None and action is None:
        # explicit steps: the action is what the last step into a relation shows (the verb with
        # a relation that does that step: move for place), else what is said
        places = [s for s in demonstration if actions.action(s.action).kind == actions.REGION and s.relation is not None]
        shown = next((v for v in actions.VERBS.values() if v.takes_relation and places[-1].action in v.steps),
                     None) if places else None
        action = ActionSpec(shown.name, places[-1].relation) if shown is not None else action_from_content(content)

    expect_value = raw.get("expect")
    if expect_value is not None and (not isinstance(expect_value, str) or expect_value not in EXPECTS):
        raise expect("expect")
    feedback = raw.get("feedback")
    if feedback is not None and feedback != FEEDBACK.get(signal):
        raise expect("feedback")
    seed = raw.get("seed")
    if seed is not None and (not isinstance(seed, int) or isinstance(seed, bool) or seed < 0):
        raise expect("seed")
    note = raw.get("note", "")
    if not isinstance(note, str):
        raise expect("note")
    comp = named("composite", composites.get)
    composite = comp.word if comp is not None else None
    if comp is not None:
        if not objects_raw:
            objects = [ObjectSpec(shape) for shape in comp.parts]
        elif len(objects) != len(comp.parts):
            raise fail("objects", f"the composite {comp.word!r} has {len(comp.parts)} parts, "
                       f"{len(objects)} objects given")
    near_miss = raw.get("near_miss", False)
    if not isinstance(near_miss, bool):
        raise expect("near_miss")
    as_said = raw.get("as_said", [])
    if not isinstance(as_said, list) or not all(isinstance(w, str) and w.strip() for w in as_said):
        raise expect("as_said")
    said_words = re.findall(r"[a-z0-9]+", content.lower())
    for w in as_said:
        ws = re.findall(r"[a-z0-9]+", w.lower())
        if not all(any(s.startswith(x) for s in said_words) for x in ws):  # ("rbox" of "rboxes")
            # a slip in it went unnoticed: the word it was meant for was asked about and skipped
            raise fail("as_said", f"{w!r} is not in the content {content!r}: as_said lists words the content says")
    if relation is None and action is None and composite is None and signal in ("inform", "verify") \
            and len(objects) >= 2 and all(o.position is None for o in objects):
        # the relation the sentence says is the layout (as `action` is read from the content):
        # without it a relation lesson was laid out at random, and taught from whatever came up
        info = read_content(content)
        if len(set(info.relations)) > 1:
            # "left of the blue cone and right of the green sphere": one layout relation cannot lay
            # out both, and the other was taught from wherever the third object fell
            said = " and ".join(f"'{r}'" for r in dict.fromkeys(info.relations))
            raise fail("content", f"the content says {said}: one 'relation' cannot lay out both; give each "
                       "object's 'position'")
        relation = info.relation
        if relation is not None and (expect_value == "failure") != info.negated:
            # the sentence is to be false ("the red box is left of ...", expect failure), or it
            # says the relation does not hold ("... is not left of ..."): close to the relation,
            # but not it (a "not" laid out in the relation was a false lesson)
            near_miss = True
    if near_miss and relation is None:
        raise fail("near_miss", "a near miss needs a 'relation' to miss")
    if signal == "inform" and "relation" in raw and relation is not None and action is None and not near_miss \
            and composite is None:
        # the lesson's own relation against what it says, as an original script's description is
        # ("red box right of blue cone", or "... is not left of ...", over relation = "left of"
        # taught the word from a scene of another, or a near miss from a scene of the word);
        # words of the teacher's own contradict nothing
        problem = legacy_content.contradiction(objects, relation, None, content, whose="the lesson")
        if problem is not None:
            raise fail("content", f"{problem}: an inform must say what its lesson lays out")

    if relation is not None and len(objects) < 2:
        raise fail("relation", f"relation {relation!r} needs two objects: objects[0] {relation} objects[1]")
    if action is not None and len(objects) < action.n_objects:
        key = "action" if "action" in raw else ("demonstration" if "demonstration" in raw else "objects")
        what = "two objects: the one moved, then the reference" if action.n_objects == 2 else "an object"
        raise fail(key, f"action {action.name!r} needs {what}")
    if signal == "react" and action is None:
        info = read_content(content)
        if info.verb is not None and info.relation is None and info.unknown:
            # "move the red box due west of the blue cone": the sentence is right, the relation
            # is the teacher's own, and the trainer cannot lay out or grade a goal it cannot read
            raise fail("content", f"the trainer knows no relation in {content!r} (a word of the teacher's own) to set "
                       f"the goal by: give action = '{info.verb} <relation>' with a relation it knows, e.g. "
                       f"'{info.verb} {relations.words()[0]}', whose region holds the teacher's")
        raise fail("content", "a react lesson needs an action: content 'move X <relation> Y' or 'push X', "
                   "or action = 'move <relation>'")
    if signal == "generate" and not objects:
        raise fail("signal", "a generate lesson needs something on the table to describe: give 'objects'")

    lesson = Lesson(signal=signal, content=content, objects=objects, relation=relation,
                    distractors=distractors, demonstration=demonstration, source=source, action=action,
                    expect=expect_value, seed=seed, note=note, near_miss=near_miss, composite=composite,
                    feedback=feedback, as_said=tuple(" ".join(w.split()) for w in as_said))
    check_lesson(lesson)
    return lesson


def _object(item: Any, i: int, n: int, loc: _Locator, source: Source) -> ObjectSpec:
    where = f"objects[{i + 1}]"
    if isinstance(item, str):
        try:
            return parse_object(item)
        except UserError as exc:
            raise source.error(f"{where}: {exc.message}", line=loc.value(n, "objects", item)) from None
    if not isinstance(item, dict):
        raise source.error(f"{where} must be a string like 'red box' or a table {{shape, colour, size, position}}",
                           line=loc.key(n, "objects"))

    def fail(needle: str, message: str) -> UserError:
        return source.error(f"{where}: {message}", line=loc.value(n, "objects", needle))

    for key in item:
        if key not in object_keys():
            raise fail(key, f"unknown key {key!r}; expected one of: {', '.join((*channels.names(), POSITION))}")
    values: dict[str, str] = {}
    for channel in channels.CHANNELS:
        given = [k for k in (channel.name, *channel.keys) if k in item]
        if len({str(item[k]) for k in given}) > 1:
            raise fail(given[1], f"both {given[0]!r} and {given[1]!r} are given, and they differ: give one")
        value = next((item[k] for k in given), None)
        if value is None:
            continue
        try:
            if not isinstance(value, str):
                raise UserError(f"expected a name, got {value!r}")
            values[channel.name] = channel.check(value)
        except UserError as exc:
            raise fail(str(value), exc.message) from None
    position = item.get("position")
    if position is not None:
        if (not isinstance(position, list) or len(position) != 2
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in position)
                or not all(math.isfinite(v) for v in position)):
            raise fail("position", "position must be [x, y] in table metres")
        position = (float(position[0]), float(position[1]))
    return ObjectSpec(appearance=values, position=position)


def _demonstration(raw: dict[str, Any], action: ActionSpec | None, n_objects: int, n: int,
                   loc: _Locator, source: Source) -> list[Step]:
    demo = raw["demonstration"]
    if demo == "auto":
        if action is None:
            raise source.error("demonstration = 'auto' needs an action: content 'move X <relation> Y' "
                               "or action = 'move <relation>'", line=loc.key(n, "demonstration"))
        return auto_demonstration(action)
    if not isinstance(demo, list) or not demo or not all(isinstance(s, str) for s in demo):
        raise source.error(f"'demonstration' must be {LESSON_KEYS['demonstration']}",
                           line=loc.key(n, "demonstration"))
    steps = []
    for text in demo:
        try:
            steps.append(parse_step(text, n_objects))
        except UserError as exc:
            raise source.error(exc.message, line=loc.value(n, "demonstration", text)) from None
    return steps
