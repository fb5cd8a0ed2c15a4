"""Lesson records: what the trainer puts on the table, says, and signals.

A lesson keeps two things apart on purpose:

* the layout (`objects`, `relation`, `distractors`): what stands on the table, for the trainer
  (`aileen.curriculum.trainer`) to build;
* the `content`: what the trainer says. In a specificity exam the two disagree ("red cone"
  said over a blue cone) and the right answer is a failure.

Both file formats (`lessonfile` for our TOML, `legacy` for the original AILEEN JSON scripts)
produce these records from the text `read_lesson_text` reads; `formats.load_curriculum` picks
the reader by file extension. The trainer's reading of its own sentences is `sentences`.
Object indices in `Step` are 0-based here (the files count from 1, as people do).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from aileen import textfile
from aileen.curriculum.sentences import read_content
from aileen.curriculum.specs import ActionSpec, ObjectSpec
from aileen.domain import actions, composites, relations
from aileen.errors import UserError, said_number
from aileen.world import catalog
from aileen.world.camera import Table

SIGNALS: tuple[str, ...] = ("inform", "verify", "react", "generate")
EXPECTS: tuple[str, ...] = ("success", "failure")


@dataclass(frozen=True)
class Source:
    """Where a lesson came from, for error messages: a file and a line and/or lesson number."""

    path: str = "<memory>"
    line: int | None = None
    index: int | None = None  # 1-based lesson number within its file
    fields: tuple[tuple[str, int], ...] = ()  # (key, line) of the lesson's keys, where known
    # The key its file's format gives what a correct learner answers with: a message asking for
    # it names the key the file can hold (an original script refuses `expect`: `is_positive`).
    expect_key: str = "expect"

    def line_of(self, key: str) -> int | None:
        """The line of one of the lesson's keys (`objects`, `demonstration`), else the lesson's."""
        return dict(self.fields).get(key, self.line)

    def where(self) -> str:
        text = f"{self.path}:{self.line}" if self.line is not None else self.path
        return f"{text}: lesson {self.index}" if self.index is not None else text

    def error(self, message: str, *, line: int | None = None) -> UserError:
        """A `UserError` located at this lesson (or at `line` in the same file)."""
        prefix = f"lesson {self.index}: " if self.index is not None else ""
        return UserError(prefix + message, path=self.path, line=line if line is not None else self.line)


def check_lesson_path(path: str | Path) -> None:
    """A `UserError` naming what `path` is when it is no lesson file to read (a folder, a
    device, a link to nothing or to itself): each was "no such lesson file"."""
    import stat

    p = Path(path)
    try:
        mode = p.stat().st_mode
    except FileNotFoundError:
        raise UserError("no such lesson file" + (" (a link to nothing)" if p.is_symlink() else ""),
                        path=str(p)) from None
    except OSError as exc:  # a link that loops, a folder that cannot be entered
        raise UserError(f"cannot read lesson file: {(exc.strerror or str(exc)).lower()}", path=str(p)) from None
    if stat.S_ISDIR(mode):
        raise UserError("is a folder, not a lesson file (give the .toml or .json files in it)", path=str(p))
    if not stat.S_ISREG(mode):
        raise UserError("is not a regular file (a device or a pipe): expected a .toml or .json lesson file",
                        path=str(p))


def read_lesson_text(path: str | Path) -> str:
    """A lesson file's text (a byte order mark at its start is read past, as editors on
    Windows write one); a missing or unreadable file is a `UserError` naming it."""
    return textfile.read_text(path, "lesson file", "no such lesson file")


@dataclass(frozen=True)
class Step:
    """One primitive action of a demonstration.

    In a lesson (`Lesson.demonstration`) `obj` and `ref` are 0-based indices into
    `Lesson.objects` and a step into a region (`place`) has either a `relation` + `ref` (the
    trainer picks the spot) or a `position`. In a concrete demonstration
    (`demonstration.demonstrate`) `obj` is a world id and every step into a region has a
    `position`; `relation`/`ref` stay as a note of why.
    """

    action: str  # a declared primitive action's name (aileen.domain.actions)
    obj: int | str
    relation: str | None = None
    ref: int | str | None = None
    position: tuple[float, float] | None = None

    @property
    def concrete(self) -> bool:
        act = actions.ACTIONS.get(self.action)
        return isinstance(self.obj, str) and (act is None or act.touches or self.position is not None)

    def __str__(self) -> str:
        def name(o: int | str | None) -> str:
            return str(o + 1) if isinstance(o, int) else str(o)

        text = f"{self.action}({name(self.obj)}"
        if self.position is not None:
            text += ", " + ", ".join(said_number(v) for v in self.position)
        text += ")"
        if self.relation is not None and self.ref is not None:
            text += f" [{self.relation} {name(self.ref)}]"
        return text


# What an original script's `[{}]` stub is skipped with (`legacy`); the run's summary counts
# these apart from lessons skipped for what they show (`report`).
EMPTY_LESSON = "an empty lesson ({}): nothing to lay out or say"


@dataclass(frozen=True)
class Lesson:
    """A scenario, an utterance and a signal; see the module docstring and docs/lessons.md."""

    signal: str
    content: str
    objects: list[ObjectSpec] = field(default_factory=list)
    relation: str | None = None  # layout: objects[0] stands in it to objects[1]
    distractors: int = 0
    demonstration: list[Step] | None = None
    source: Source = Source()
    action: ActionSpec | None = None  # for action lessons: objects[0] is moved, objects[1] the reference
    expect: str | None = None  # "success" / "failure": what a correct learner answers
    seed: int | None = None  # layout seed; None: the curriculum's seed and the lesson's number
    note: str = ""
    # Lay the relation out as a near miss: close to it, but not it (the right answer to a
    # verify is then a failure).
    near_miss: bool = False
    # The trainer's verdict after the answer (agent/feedback.py): "wrong" (verify: when the
    # answer is wrong, the trainer says so), "confirm" (react: the trainer confirms a reached goal).
    feedback: str | None = None
    composite: str | None = None  # a composite word: the objects are its parts, laid out as it says
    # The trainer says something false about the scene it lays out (the original scripts'
    # `is_positive: "False"` without `content`); decided at layout (`curriculum.falsehood`).
    say_false: bool = False
    concept: str | None = None  # a generate lesson's `concept` field in the original scripts (kept, not used)
    # The sentence was generated from a description that leaves colours or shapes open (the
    # original scripts' `<obj1>` placeholders): the trainer draws them and says the sentence
    # with what it drew (`curriculum.placeholders.name`), before the lesson is laid out.
    name_objects: bool = False
    # Words the trainer means as said: the agent's "did you mean 'box'?" about "rox" is
    # answered no (`Interpreter._ask`; a lesson file's `as_said`, the web console's "no").
    as_said: tuple[str, ...] = ()
    # A lesson the file holds but that says nothing to run (the original's `[{}]` stubs): it is
    # skipped with this reason, as a lesson the trainer cannot lay out is, and the run goes on.
    skip: str | None = None
    # Objects earlier lessons of the file said this lesson's unread words of (words the
    # trainer's own language does not hold, "kube" taught on a red box): its distractors keep
    # clear of them (`trainer.distractor_kinds`). Filled by `said_of_unread`.
    unread_said_of: tuple[ObjectSpec, ...] = ()

    def summary(self) -> str:
        """One line for transcripts: `inform "red box" | table: red box + 2 distractors`."""
        table = ", ".join(o.describe() for o in self.objects) or "nothing"
        if self.relation is not None and len(self.objects) >= 2:
            table = f"{self.objects[0].describe()} {self.relation} {self.objects[1].describe()}"
        if self.distractors:
            table += f" + {self.distractors} distractor{'s' if self.distractors > 1 else ''}"
        text = f'{self.signal} "{self.content}" | table: {table}'
        if self.demonstration is not None:
            text += f" | shown: {self.action.name if self.action else 'steps'}"
        if self.expect is not None:
            text += f" | expect {self.expect}"
        return text

    @property
    def kind(self) -> str:
        """`action`, `spatial` or `visual`: what sort of word the lesson is about."""
        if self.action is not None or self.demonstration is not None:
            return "action"
        if self.relation is not None or read_content(self.content).relation is not None:
            return "spatial"
        return "visual"


@dataclass(frozen=True)
class Curriculum:
    """An ordered list of lessons and the defaults they share."""

    lessons: list[Lesson]
    seed: int = 0
    title: str = ""
    path: str = ""
    after: tuple[str, ...] = ()  # lesson files beside it whose words it takes as known (`after = [...]`)

    def __iter__(self) -> Iterator[Lesson]:
        return iter(self.lessons)

    def __len__(self) -> int:
        return len(self.lessons)

    def __getitem__(self, i: int) -> Lesson:
        return self.lessons[i]

    def lesson_seed(self, i: int) -> int:
        """The layout seed of lesson i (0-based): its own, or derived from the curriculum's."""
        own = self.lessons[i].seed
        return own if own is not None else self.seed * 1000 + i


def said_of_unread(lessons: list[Lesson]) -> list[Lesson]:
    """The lessons, each knowing the objects earlier ones said its unread words of.

    The trainer cannot read "kube", so it cannot tell whether a distractor is one; it knows
    what it laid out when it said the word before (not in an exam whose answer is a failure:
    that sentence was false of its objects). Both file formats call this once they have read
    every lesson."""
    said: dict[str, list[ObjectSpec]] = {}
    out: list[Lesson] = []
    for lesson in lessons:
        words = dict.fromkeys(read_content(lesson.content).unknown) if lesson.content else {}
        known = tuple(dict.fromkeys(o for w in words for o in said.get(w, ())))
        out.append(dataclasses.replace(lesson, unread_said_of=known) if known else lesson)
        if lesson.expect != "failure" and lesson.skip is None and not lesson.say_false:
            for w in words:
                said.setdefault(w, []).extend(lesson.objects)
    return out


def goal_relation(lesson: Lesson) -> str | None:
    """The relation an action lesson's goal names (`move X right of Y`: "right of"), else None."""
    return lesson.action.relation if lesson.action is not None else None


def auto_demonstration(action: ActionSpec) -> list[Step]:
    """The trainer's own demonstration of its verb, its declared steps on object 1 (a step into
    a region: <rel> object 2): `move X <rel> Y` picks X up and places it <rel> Y; `push X`
    pushes X."""
    out = []
    for name in actions.verb(action.verb).steps:
        if actions.ACTIONS[name].kind == actions.REGION:
            out.append(Step(name, 0, relation=action.relation, ref=1))
        else:
            out.append(Step(name, 0))
    return out


def parse_step(text: str, n_objects: int) -> Step:
    """`pick_up 1`, `point 2`, `place 1 right of 2`, `place 1 at 0.3 0.6` (objects count from 1)."""
    words = text.replace(",", " ").split()
    expected = ("expected " + ", ".join(f"'{a.syntax}'" for a in actions.ACTIONS.values())
                + f" (N, M between 1 and {n_objects})")
    if len(words) < 2:
        raise UserError(f"cannot read step {text!r}; {expected}")
    try:
        action = actions.action(words[0]).name
    except UserError:
        raise UserError(f"unknown action {words[0]!r} in step {text!r}; {expected}") from None

    def index(word: str) -> int:
        if not word.isdigit() or not 1 <= int(word) <= n_objects:
            raise UserError(f"bad object number {word!r} in step {text!r}; {expected}")
        return int(word) - 1

    obj = index(words[1])
    rest = words[2:]
    if actions.ACTIONS[action].touches:
        if rest:
            raise UserError(f"unexpected {' '.join(rest)!r} in step {text!r}; {expected}")
        return Step(action, obj)
    if not rest:
        raise UserError(f"step {text!r} says where to place nothing; {expected}")
    if rest[0].lower() == "at":
        if len(rest) != 3:
            raise UserError(f"cannot read position in step {text!r}; {expected}")
        try:
            x, y = float(rest[1]), float(rest[2])
        except ValueError:
            raise UserError(f"cannot read position in step {text!r}; {expected}") from None
        return Step(action, obj, position=(x, y))
    ref = index(rest[-1])
    relation = relations.find(" ".join(rest[:-1]))
    if relation is None:
        raise UserError(f"unknown relation {' '.join(rest[:-1])!r} in step {text!r}; "
                        f"expected one of: {', '.join(relations.known())}")
    if ref == obj:
        raise UserError(f"step {text!r} places an object relative to itself")
    return Step(action, obj, relation=relation, ref=ref)


def most_distractors() -> int:
    """The most distractors a lesson may ask for: as many of the smallest objects as the table
    holds side by side. Fewer than that which do not fit are laid out as many as fit (the
    transcript says so); more is a slip in the file (`1e20` was accepted and printed back)."""
    return Table().room(min(catalog.SIZES.values()))


def check_lesson(lesson: Lesson) -> None:
    """Consistency checks shared by both readers; raises the lesson's located `UserError`."""
    src = lesson.source
    if lesson.signal not in SIGNALS:
        raise src.error(f"signal {lesson.signal!r} must be one of {', '.join(SIGNALS)}")
    if lesson.relation is not None and len(lesson.objects) < 2:
        raise src.error(f"relation {lesson.relation!r} needs two objects (objects[0] {lesson.relation} objects[1])")
    if lesson.action is not None and len(lesson.objects) < lesson.action.n_objects:
        raise src.error(f"action {lesson.action.name!r} needs {lesson.action.n_objects} objects"
                        + (" (the one moved, then the reference)" if lesson.action.n_objects == 2 else ""))
    if lesson.distractors < 0:
        raise src.error("distractors must be a whole number >= 0")
    if lesson.distractors > most_distractors():
        raise src.error(f"distractors must be at most {most_distractors()} (the table holds no more of the "
                        f"smallest objects side by side), found {str(lesson.distractors)[:40]}",
                        line=src.line_of("distractors"))
    if lesson.signal != "generate" and lesson.skip is None and not any(ch.isalnum() for ch in lesson.content):
        # "?!" is no sentence: the agent read it as empty and the lesson ran for nothing
        raise src.error(f"'content' {lesson.content!r} says no word: give what the trainer says",
                        line=src.line_of("content"))
    if lesson.action is not None and lesson.action.relation is not None \
            and lesson.action.relation not in relations.placeable():
        raise src.error(f"cannot '{lesson.action.verb}' an object {lesson.action.relation!r} another: where it "
                        f"stands does not decide that; expected one of: {', '.join(relations.placeable())}")
    if (lesson.action is not None and lesson.action.relation is not None and not lesson.near_miss
            and lesson.relation == lesson.action.relation):
        # `relation` lays out the start, where the goal must be clearly false: a react laid out
        # at its goal was graded reached with the agent doing nothing
        raise src.error(f"relation {lesson.relation!r} lays out the start of an action whose goal is "
                        f"{lesson.relation!r}: the start must not show the goal; leave `relation` out (the "
                        f"trainer lays the start out with the goal clearly false) or give another",
                        line=src.line_of("relation"))
    if lesson.composite is not None:
        comp = composites.get(lesson.composite)
        if len(lesson.objects) != len(comp.parts):
            raise src.error(f"the composite {comp.word!r} has {len(comp.parts)} parts; the lesson gives "
                            f"{len(lesson.objects)} objects")
    if lesson.seed is not None and lesson.seed < 0:
        raise src.error(f"seed {lesson.seed} must be a whole number >= 0", line=src.line_of("seed"))
    # The agent reads the sentence when the lesson runs: one it cannot read is its answer
    # ("not understood", not graded), not a mistake in the file. A sentence that is empty or
    # longer than the agent reads at all is, and stops the run before the first lesson.
    from aileen.reasoning import language

    try:
        if lesson.content or lesson.signal != "generate":
            language.parse(lesson.content)
    except language.TooLong as exc:
        raise src.error(exc.message, line=src.line_of("content")) from None
    except language.NotUnderstood as exc:
        if not lesson.content.strip():
            raise src.error(exc.message, line=src.line_of("content")) from None
