"""The evolution-strategy loop over a settings file, end to end on a toy score."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml

from learning.param_search import Knob, Search, overrides, run_search


def _read_x(task: tuple[str, int]) -> float:
    """A worker: the candidate file's ``toy.x`` (the seed offset is ignored)."""
    path, _offset = task
    return float(yaml.safe_load(Path(path).read_text())["toy"]["x"])


@dataclass(frozen=True)
class _Scored:
    score: float

    def describe(self) -> str:
        return f"score {self.score:+.3f}"


def test_the_loop_writes_candidates_scores_them_and_moves_the_mean(tmp_path, capsys):
    source = tmp_path / "toy.yaml"
    source.write_text("toy: {x: 0.0, kept: 7}\n")
    knobs = (Knob("toy.x", -1.0, 1.0, 0.2),)
    search = Search(
        knobs=knobs,
        start=np.array([0.0]),
        source=source,
        tasks=lambda path, offset: [(path, offset)],
        worker=_read_x,
        score=lambda results: _Scored(-((results[0] - 0.6) ** 2)),
    )
    out = tmp_path / "result.json"
    mean = run_search(search, out, minutes=10.0, generations=25, population=6, jobs=1)
    assert abs(mean[0] - 0.6) < 0.1
    saved = json.loads(out.read_text())
    assert saved["generation"] == 25 and saved["set"] == overrides(knobs, mean)
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "packaged settings: score -0.360"
    assert lines[-1] == f"--set toy.x={mean[0]:.6g}"
    assert yaml.safe_load(source.read_text()) == {"toy": {"x": 0.0, "kept": 7}}
