"""The benchmarks' plots: a PNG with one panel per group and every phase in gait order."""

from __future__ import annotations

from benchmarks.plots import phase_distance_plot, phase_order


def test_phases_run_left_step_then_right_step():
    order = phase_order()
    assert len(order) == len(set(order)) == 16
    assert order[:8] == [(t, True) for t in range(8)]
    assert order[8:] == [(t, False) for t in range(8)]


def test_phase_distance_plot_writes_a_png_even_with_phases_missing(tmp_path):
    samples = {(t, True): [0.3, 0.35, 0.4] for t in range(8)}  # the right leg's step missing
    path = phase_distance_plot({"DFDL": samples, "LFDL": samples}, tmp_path / "p" / "d.png")
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 5_000
