"""What the page shows of the table: the camera image and the agent's perception of it.

Why a module of its own (split out of `session`): turning what an agent perceived into the
page's marks (boxes, ids, the objects a sentence grounded to, the relation it stated as an
arrow) and images is a job apart from teaching; it reads perception, never changes the
trainer's agent. Between lessons the image is the preview: the table laid out and
photographed exactly as the next lesson will, perceived by a second, memory-less agent
(`eyes`), so the trainer's agent never perceives anything outside a lesson and its episodic
memory matches a replay. After a lesson it is the lesson's last frame as the agent saw it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from aileen.agent import Agent
from aileen.agent.body import WorldBody
from aileen.curriculum import trainer
from aileen.curriculum.interpreter import CAMERA_NOISE
from aileen.curriculum.lesson import Lesson, Source
from aileen.domain import relations
from aileen.errors import UserError
from aileen.web import overlay
from aileen.web.table import Placed
from aileen.world.camera import Camera
from aileen.world.render import Frame


@dataclass
class View:
    """What the page shows: a camera image and the agent's perception of it."""

    image: np.ndarray
    marks: list[overlay.Mark]
    highlight: list[str] = field(default_factory=list)
    frames: list[np.ndarray] = field(default_factory=list)  # a lesson's frames, for playback
    arrows: list[overlay.Arrow] = field(default_factory=list)  # relations between grounded objects
    pngs: dict[bool, bytes] = field(default_factory=dict)  # encoded once, by overlay on/off

    def png(self, *, overlay_on: bool, frame: int | None = None) -> bytes:
        """The image with the perception drawn over it (or not), or a lesson's frame as taken."""
        if frame is None:
            if overlay_on not in self.pngs:
                self.pngs[overlay_on] = overlay.png(overlay.draw(self.image, self.marks, self.highlight,
                                                                 overlay=overlay_on, arrows=self.arrows))
            return self.pngs[overlay_on]
        if not isinstance(frame, int) or not 0 <= frame < len(self.frames):
            raise UserError(f"no frame {frame!r}; the last lesson has {len(self.frames)}")
        return overlay.png(overlay.draw(self.frames[frame], overlay=False))


def preview(objects: list[Placed], camera: Camera, eyes: Agent, seed: int) -> View:
    """The next lesson's camera image of the table, as the memory-less eyes perceive it."""
    lesson = Lesson("inform", "", [o.spec() for o in objects], source=Source("<console>"))
    if lesson.objects:
        world = trainer.layout(lesson, seed=seed, table=camera.table).world
    else:
        from aileen.world.sim import World

        world = World(camera.table, seed=seed)
    image = WorldBody(world, camera, seed=seed, noise=CAMERA_NOISE).look()
    eyes.new_scene()
    state = eyes.perceive(image)
    return View(image, marks_of(state))


def after_lesson(seen_state, referents: dict[str, list[str]], image: np.ndarray, frames: list[Frame],
                 said: str | None, *, denied: bool) -> View:
    """What the agent saw at the end of a lesson: its objects, those the sentence grounded to
    lit, and the relation the sentence (`said`) stated between them."""
    marks = marks_of(seen_state) if seen_state is not None else []
    lit = sorted({i for ids in referents.values() for i in ids})
    drawn = arrows(said or "", referents, {m.id for m in marks}, denied=denied)
    return View(image, marks, lit, [f.image for f in frames], arrows=drawn)


def objects_json(objects: list[Placed], camera: Camera, marks: list[overlay.Mark]) -> list[dict]:
    """The table as the trainer knows it (for editing), each object with the id the agent
    gave what it saw there."""
    out = []
    for i, o in enumerate(objects):
        u, v = camera.to_pixels(o.x, o.y)
        out.append({"index": i, **o.appearance, "x": o.x, "y": o.y,
                    "px": [round(u, 1), round(v, 1)], "half_px": round(o.half * camera.width / camera.table.width, 1),
                    "distractor": o.distractor, "name": o.describe(), "seen_id": seen_at(marks, u, v)})
    return out


def marks_of(seen_state) -> list[overlay.Mark]:
    return [overlay.Mark(s.id, s.percepts, s.box_px, s.under) for _, s in sorted(seen_state.objects.items())]


def seen_at(marks: list[overlay.Mark], u: float, v: float) -> str | None:
    """The agent's id for the object whose centre is at camera pixel (u, v): the perceived box
    around that pixel, the nearest centre first; None when the agent saw nothing there."""
    best, best_d = None, float("inf")
    for m in marks:
        if m.under is not None:
            continue  # kept in mind, not seen: the pixel shows what lies over it
        u0, v0, u1, v1 = m.box_px
        if u0 - 2 <= u <= u1 + 2 and v0 - 2 <= v <= v1 + 2:
            d = ((u0 + u1) / 2 - u) ** 2 + ((v0 + v1) / 2 - v) ** 2
            if d < best_d:
                best, best_d = m.id, d
    return best


def arrows(sentence: str, referents: dict[str, list[str]], seen: set[str], *,
           denied: bool = False) -> list[overlay.Arrow]:
    """The relation a sentence states, between the objects its phrases grounded to: an arrow
    from the first phrase's object to the second's, with the relation's words as said ("not
    left of" when the agent `denied` it). The trainer's reading of its own sentence finds the
    relation words (`relations.phrases`)."""
    text = " " + " ".join(sentence.lower().split()) + " "
    for spelling, _word in relations.phrases():
        at = text.find(f" {spelling} ")
        if at >= 0:
            break
    else:
        return []
    before = [k for k in referents if 0 <= text.find(k.lower()) < at]
    after = [k for k in referents if text.find(k.lower(), at + len(spelling) + 1) > at]
    if len(before) != 1 or len(after) != 1:
        return []
    pairs = [(a, b) for a in referents[before[0]] for b in referents[after[0]] if a != b and a in seen and b in seen]
    return [overlay.Arrow(a, b, f"not {spelling}" if denied else spelling) for a, b in pairs[:4]]
