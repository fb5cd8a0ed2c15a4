"""The agent's body: eyes (a camera over the table) and a hand (the primitive actions that
`aileen.domain.actions` declares: point, pick up, place, push, ...).

The agent addresses objects the way a robot would, by where they are in its own image, and
never by the simulator's ids; this module is the only bridge from agent to world, so the
agent cannot read ground truth by accident.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from aileen.domain import actions
from aileen.errors import UserError
from aileen.world.camera import DEFAULT_CAMERA, Camera
from aileen.world.render import Frame, render
from aileen.world.sim import SettleReport, World


@dataclass
class WorldBody:
    world: World
    camera: Camera = DEFAULT_CAMERA
    seed: int | None = None  # lighting/noise of the camera; each look draws the next frame
    noise: float = 0.0
    # Called with every rendered frame (image + ground truth). Only experiment ablations use
    # it (`--perception truth`, to tell perception errors from learning errors); the agent
    # itself only ever receives the image.
    on_frame: Callable[[Frame], None] | None = None
    _frames: int = field(default=0, init=False)
    last_settle: SettleReport | None = field(default=None, init=False)

    def look(self) -> np.ndarray:
        """An RGB image of the table as it is now."""
        seed = None if self.seed is None else self.seed * 100_003 + self._frames
        self._frames += 1
        frame = render(self.world, camera=self.camera, seed=seed, noise=self.noise)
        if self.on_frame is not None:
            self.on_frame(frame)
        return frame.image

    def object_at(self, u: float, v: float) -> str:
        """The simulator id of the object drawn at pixel (u, v) (the hand's touch sensor)."""
        x, y = self.camera.to_metres(u, v)
        best, best_d = None, float("inf")
        for obj in self.world.objects():
            if obj.held:
                continue
            x0, y0, x1, y1 = obj.box_m()
            if x0 <= x <= x1 and y0 <= y <= y1:
                d = (obj.x - x) ** 2 + (obj.y - y) ** 2
                if d < best_d:
                    best, best_d = obj.id, d
        if best is None:
            raise UserError(f"there is no object at pixel ({u:.0f}, {v:.0f})")
        return best

    def touch(self, action: str, u: float, v: float) -> SettleReport | None:
        """Do a primitive action that goes to the object seen at pixel (u, v) (one declared of
        kind `touch`: point, pick up, push, ...)."""
        act = actions.action(action)
        if not act.touches:
            raise UserError(f"{act.name} is not done to an object at a pixel")
        report = self._done(act.world, self.object_at(u, v), None, None)
        if report is not None:
            self.last_settle = report
        return report

    def put(self, action: str, x: float, y: float, *, at: tuple[float, float] | None = None,
            onto: tuple[float, float] | None = None) -> SettleReport | None:
        """Do a primitive action that puts an object into a region (one declared of kind
        `region`) with its centre at (x, y) in table metres: the held object for an action that
        releases it (place), else the object seen at pixel `at`; with `onto` (a pixel), on top
        of the object seen there."""
        act = actions.action(action)
        if act.touches:
            raise UserError(f"{act.name} is done to an object at a pixel, not into a region")
        if act.hand == actions.RELEASE:
            obj = self.world.held
            if obj is None:
                raise UserError(f"nothing is held, so {act.name} has nothing to put down")
        elif at is not None:
            obj = self.object_at(*at)
        else:
            raise UserError(f"{act.name} needs the pixel of the object it is done to")
        support = self.object_at(*onto) if onto is not None else None
        report = self._done(act.world, obj, (x, y), support)  # settles the table
        if report is not None:
            self.last_settle = report
        return report

    def _done(self, call, obj: str, position, support):  # noqa: ANN001, ANN202 - actions.WorldCall
        """The world does the action; what it refuses is said with the objects as they look
        ("cannot place the red box on the green cylinder"): the simulator's own ids ("obj3")
        read as the agent's ("o3"), another object."""
        try:
            return call(self.world, obj, position, support)
        except UserError as exc:
            def said(m: re.Match) -> str:
                try:
                    o = self.world.get(m.group(0))
                except (KeyError, UserError):
                    return m.group(0)
                return f"the {o.colour} {o.shape}"

            raise UserError(re.sub(r"\bobj\d+\b", said, exc.message)) from None

    def place(self, x: float, y: float, *, onto: tuple[float, float] | None = None) -> SettleReport | None:
        """Put the held object down with its centre at (x, y) in table metres; with `onto`
        (a pixel), on top of the object seen there (`put` with the action "place")."""
        return self.put("place", x, y, onto=onto)
