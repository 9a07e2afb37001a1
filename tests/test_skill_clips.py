"""Skill clips: a short walk clip renders to a GIF whose frames show the robot moving."""

from __future__ import annotations

import pytest

pytest.importorskip("pybullet")
PIL = pytest.importorskip("PIL")

from learning.skill_clips import CLIPS, main, render_clip  # noqa: E402


def test_walk_clip_renders_frames_that_change(tmp_path):
    from PIL import Image, ImageChops

    path = render_clip("walk", tmp_path / "walk.gif", seconds=0.6, every=10)
    image = Image.open(path)
    assert image.n_frames == 3
    first = image.convert("RGB")
    image.seek(2)
    last = image.convert("RGB")
    assert ImageChops.difference(first, last).getbbox() is not None


def test_clip_listing_and_unknown_names(capsys):
    assert main(["--list"]) == 0
    assert set(capsys.readouterr().out.split()) >= {f"{name}:" for name in CLIPS}
    with pytest.raises(SystemExit):
        main(["moonwalk"])
    assert "unknown clip(s) ['moonwalk']" in capsys.readouterr().err
