"""An evolution-strategy search over keys of a skill's YAML settings file.

The walk and dribble searches (``learning/walk_search.py``, ``learning/dribble_search.py``)
share this loop: a :class:`~learning.snes.SNES` over :class:`Knob` values, each candidate
written as a copy of the settings file with its keys changed (the benchmarks' ``--set``
overrides), scored by running the packaged benchmark code on worker processes. Each
generation plays its own seeds (every candidate of a generation the same ones), so the
search cannot fit one chaotic trajectory; the result is the search's mean, scored every
generation and written to a JSON file as ``--set`` strings.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from multiprocessing import Pool
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from benchmarks.dribble import with_settings
from learning.snes import SNES


@dataclass(frozen=True)
class Knob:
    """One searched setting: its dotted key in the settings file, its range and the search's
    start spread for it."""

    key: str
    low: float
    high: float
    spread: float


class Scored(Protocol):
    """What a candidate's evaluation must give: a score (higher is better) and a line."""

    score: float

    def describe(self) -> str: ...


def overrides(knobs: Sequence[Knob], values: Sequence[float]) -> list[str]:
    """``--set`` strings (``dotted.key=value``) for a parameter vector."""
    return [f"{k.key}={v:.6g}" for k, v in zip(knobs, values, strict=True)]


def clipped_start(knobs: Sequence[Knob], values: Sequence[float]) -> np.ndarray:
    """Start values clipped into their knobs' ranges."""
    return np.array([min(max(float(v), k.low), k.high) for k, v in zip(knobs, values, strict=True)])


class CandidateFiles:
    """Writes each candidate's settings copy under its own folder: the skills cache their
    settings by path, so a reused path would keep an older candidate's values."""

    def __init__(self, folder: Path, source: Path) -> None:
        self.folder = folder
        self.source = source
        self.count = 0

    def write(self, changes: list[str]) -> Path:
        self.count += 1
        own = self.folder / f"candidate{self.count:06d}"
        own.mkdir()
        return with_settings(changes, own, self.source)


#: (candidate file, seed offset) -> the candidate's run results, one task per element
Tasks = Callable[[str, int], list[Any]]


@dataclass(frozen=True)
class Search:
    """What one search needs: its knobs and start values, the settings file the candidates
    copy, the tasks of one candidate, the worker function that runs a task, and how a
    candidate's task results become a score."""

    knobs: Sequence[Knob]
    start: np.ndarray
    source: Path
    tasks: Tasks
    worker: Callable[[Any], Any]
    score: Callable[[list[Any]], Scored]


def _evaluate(
    search: Search, pool: Any, files: CandidateFiles, candidates: np.ndarray, offset: int
) -> list[Scored]:
    paths = [str(files.write(overrides(search.knobs, c))) for c in candidates]
    per_candidate = [search.tasks(p, offset) for p in paths]
    flat = [task for tasks in per_candidate for task in tasks]
    results = pool.map(search.worker, flat, chunksize=1)
    scored, at = [], 0
    for tasks in per_candidate:
        scored.append(search.score(results[at : at + len(tasks)]))
        at += len(tasks)
    return scored


def run_search(
    search: Search,
    out: Path,
    minutes: float,
    generations: int = 1000,
    population: int | None = None,
    jobs: int = 2,
    seed: int = 0,
    seed_step: int = 10,
) -> np.ndarray:
    """Run the SNES until ``minutes`` or ``generations`` are used up, printing each
    generation's mean score and best sample and writing the mean to ``out``; returns it."""
    es = SNES(
        search.start,
        np.array([k.spread for k in search.knobs]),
        np.array([k.low for k in search.knobs]),
        np.array([k.high for k in search.knobs]),
        population=population,
        seed=seed,
    )
    began = time.monotonic()
    with tempfile.TemporaryDirectory() as folder, Pool(jobs) as pool:
        files = CandidateFiles(Path(folder), search.source)
        base = _evaluate(search, pool, files, search.start[None], 0)[0]
        print(f"packaged settings: {base.describe()}", flush=True)
        for generation in range(1, generations + 1):
            offset = seed_step * generation
            results = _evaluate(search, pool, files, es.ask(), offset)
            es.tell(np.array([r.score for r in results]))
            best = max(results, key=lambda r: r.score)
            mean = _evaluate(search, pool, files, es.mean[None], offset)[0]
            elapsed = (time.monotonic() - began) / 60.0
            print(
                f"generation {generation} ({elapsed:.1f} min): mean {mean.describe()}; "
                f"best sample {best.describe()}",
                flush=True,
            )
            _save(out, search.knobs, es, mean, generation)
            if elapsed >= minutes:
                break
    print(" ".join(f"--set {s}" for s in overrides(search.knobs, es.mean)))
    return es.mean


def _save(out: Path, knobs: Sequence[Knob], es: SNES, mean: Scored, generation: int) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    data = {
        "set": overrides(knobs, es.mean),
        "mean_scored": mean.describe(),
        "generation": generation,
        "spread": [float(v) for v in es.spread],
    }
    out.write_text(json.dumps(data, indent=1) + "\n")


def add_search_arguments(parser: argparse.ArgumentParser) -> None:
    """The options every search takes: where it starts, how long it runs, its result file."""
    parser.add_argument(
        "--start-set",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="start from the settings file with these keys changed (an earlier result)",
    )
    parser.add_argument("--minutes", type=float, default=60.0)
    parser.add_argument("--generations", type=int, default=1000)
    parser.add_argument("--population", type=int, default=None)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, required=True)


def run_from_arguments(
    args: argparse.Namespace, settings: Path, build: Callable[[Path], Search]
) -> np.ndarray:
    """Run the search ``build`` makes from ``settings`` (a copy with ``--start-set``'s keys
    changed, if any) with the options of :func:`add_search_arguments`; returns the mean."""
    with tempfile.TemporaryDirectory() as folder:
        source = settings
        if args.start_set:
            source = with_settings(args.start_set, Path(folder), settings)
        return run_search(
            build(source),
            args.out,
            args.minutes,
            args.generations,
            args.population,
            args.jobs,
            args.seed,
        )
