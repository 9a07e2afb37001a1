"""Plots of benchmark figures people would rather see than read (PNG, matplotlib).

matplotlib is an optional dependency (``pip install -e ".[plots]"``): the benchmarks print their
``name: value`` lines without it, and only ``--plot`` needs it, so a playing agent or a CI run
never imports it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

#: one phase of a gait: (t, left_active)
Phase = tuple[int, bool]


def _pyplot():
    """matplotlib's pyplot on the headless Agg backend, or a clear error naming the extra."""
    try:
        import matplotlib
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise SystemExit(
            'plots need matplotlib: .venv/bin/pip install -e ".[plots]" (or pip install matplotlib)'
        ) from exc
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def phase_order() -> list[Phase]:
    """The 16 phases in the order a gait runs them: the left leg's step, then the right's."""
    return [(t, True) for t in range(8)] + [(t, False) for t in range(8)]


def phase_distance_plot(
    groups: Mapping[str, Mapping[Phase, Sequence[float]]], path: Path, title: str = ""
) -> Path:
    """Box plots of the torso-to-ball distance per phase, one panel per group (a gait on a
    robot type): what the dribble benchmark's per-phase medians summarise, with the spread.

    ``groups`` maps a panel's label to its samples per phase (every cycle of every run)."""
    plt = _pyplot()
    phases = phase_order()
    labels = [f"{t}{'L' if left else 'R'}" for t, left in phases]
    fig, axes = plt.subplots(
        len(groups), 1, figsize=(9, 2.4 * len(groups)), squeeze=False, sharex=True
    )
    for ax, (label, samples) in zip(axes[:, 0], groups.items(), strict=True):
        data = [list(samples.get(phase, ())) or [float("nan")] for phase in phases]
        ax.boxplot(data, showfliers=False, whis=(5, 95))
        ax.set_ylabel("ball m")
        ax.set_title(label, fontsize=10, loc="left")
        ax.grid(axis="y", alpha=0.3)
        ax.axvline(8.5, color="grey", lw=0.8)
    axes[-1, 0].set_xticks(range(1, len(labels) + 1), labels)
    axes[-1, 0].set_xlabel("phase (t, L = left leg swings, R = right leg swings)")
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path
