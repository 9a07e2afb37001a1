"""Headless rendering: a frame shows the scene (the orange ball on the grass); GIFs are saved."""

from __future__ import annotations

import numpy as np
from PIL import Image

from sim.render import BALL_COLOUR, Renderer, save_gif
from sim.session import Session, SessionConfig


def test_frame_shows_the_ball_and_gif_is_written(tmp_path):
    session = Session(SessionConfig(seed=0))
    try:
        renderer = Renderer(session, width=160, height=120)
        frame = renderer.frame(distance=0.6)
        assert frame.shape == (120, 160, 3) and frame.dtype == np.uint8
        orange = np.array(BALL_COLOUR[:3]) * 255
        close = np.linalg.norm(frame.astype(float) - orange, axis=-1) < 60
        assert close.sum() > 20, "the ball should fill part of a close-up frame"
        path = save_gif([frame, frame[::-1]], tmp_path / "clip.gif", fps=5)
        assert Image.open(path).n_frames == 2
    finally:
        session.close()
