"""Headless pictures of a session: PyBullet's software renderer, frames to PNG or GIF.

Rendering adds visual-only bodies (field lines, no collision shape, no mass) and colours, so it
never changes the physics; it is meant for README clips and for looking at a skill, not for
vision (agents see through the ``See`` perceptor).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pybullet

from world.field_geometry import FIELD_LINES

GRASS = (0.18, 0.55, 0.22, 1.0)
LINE = (0.95, 0.95, 0.95, 1.0)
TEAM_COLOURS = {
    "left": (0.25, 0.45, 0.95, 1.0),
    "right": (0.9, 0.3, 0.25, 1.0),
    None: (0.7,) * 3 + (1,),
}
BALL_COLOUR = (1.0, 0.55, 0.1, 1.0)
LINE_WIDTH = 0.05


class Renderer:
    """Pictures of one :class:`~sim.session.Session`, from a camera aimed at a point."""

    def __init__(self, session, width: int = 480, height: int = 320) -> None:
        self.session = session
        self.width, self.height = width, height
        self._client = session.world.client
        self._coloured: set[tuple[int, str | None]] = set()
        pybullet.changeVisualShape(
            session.field.ground_id, -1, rgbaColor=GRASS, physicsClientId=self._client
        )
        pybullet.changeVisualShape(
            session.ball.body_id, -1, rgbaColor=BALL_COLOUR, physicsClientId=self._client
        )
        self._line_ids = [self._add_line(begin, end) for begin, end in FIELD_LINES]

    def _add_line(self, begin: Sequence[float], end: Sequence[float]) -> int:
        """A flat white box on the grass: visual only (no collision shape, no mass)."""
        (x0, y0, _), (x1, y1, _) = begin, end
        length = math.hypot(x1 - x0, y1 - y0)
        visual = pybullet.createVisualShape(
            pybullet.GEOM_BOX,
            halfExtents=[length / 2, LINE_WIDTH / 2, 0.001],
            rgbaColor=LINE,
            physicsClientId=self._client,
        )
        yaw = math.atan2(y1 - y0, x1 - x0)
        return pybullet.createMultiBody(
            baseMass=0,
            baseCollisionShapeIndex=-1,
            baseVisualShapeIndex=visual,
            basePosition=[(x0 + x1) / 2, (y0 + y1) / 2, 0.001],
            baseOrientation=pybullet.getQuaternionFromEuler([0, 0, yaw]),
            physicsClientId=self._client,
        )

    def _colour_robots(self) -> None:
        for slot in self.session.agents.values():
            if slot.robot is None or (slot.robot.body_id, slot.side) in self._coloured:
                continue
            body = slot.robot.body_id
            colour = TEAM_COLOURS.get(slot.side, TEAM_COLOURS[None])
            for link in range(-1, pybullet.getNumJoints(body, physicsClientId=self._client)):
                pybullet.changeVisualShape(
                    body, link, rgbaColor=colour, physicsClientId=self._client
                )
            self._coloured.add((body, slot.side))

    def frame(
        self,
        target: Sequence[float] | None = None,
        distance: float = 2.0,
        yaw_deg: float = -60.0,
        pitch_deg: float = -25.0,
    ) -> np.ndarray:
        """An RGB image (height, width, 3) of the scene around ``target`` (default: the ball)."""
        self._colour_robots()
        target = list(target if target is not None else self.session.ball.position())
        view = pybullet.computeViewMatrixFromYawPitchRoll(
            target, distance, yaw_deg, pitch_deg, 0.0, 2, physicsClientId=self._client
        )
        projection = pybullet.computeProjectionMatrixFOV(
            50.0, self.width / self.height, 0.05, 100.0, physicsClientId=self._client
        )
        _, _, rgba, _, _ = pybullet.getCameraImage(
            self.width,
            self.height,
            view,
            projection,
            renderer=pybullet.ER_TINY_RENDERER,
            physicsClientId=self._client,
        )
        return np.reshape(np.asarray(rgba, dtype=np.uint8), (self.height, self.width, 4))[..., :3]


def save_gif(frames: Sequence[np.ndarray], path: str | Path, fps: float = 10.0) -> Path:
    """Write frames as a looping GIF (Pillow)."""
    from PIL import Image

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    images = [Image.fromarray(frame) for frame in frames]
    images[0].save(path, save_all=True, append_images=images[1:], duration=int(1000 / fps), loop=0)
    return path
