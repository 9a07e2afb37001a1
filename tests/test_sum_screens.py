"""Summing the per-seed lines of several get-up screen logs (scripts/get_up/sum_screens.py)."""

from scripts.get_up.sum_screens import read_rows


def test_completed_seed_lines_are_read_and_everything_else_is_skipped(tmp_path):
    (tmp_path / "screen_0.log").write_text(
        "pybullet build time: Jan 29 2025\n"
        "seed 100000 (20 trials): 14  17  14\n"
        "seed 100500 (20 trials): 15  16  14\n"
        "  29  base\n"
    )
    (tmp_path / "screen_1.log").write_text("seed 102500 (19 trials): 11 12 13\nTraceback ...\n")
    (tmp_path / "notes.txt").write_text("seed 1 (20 trials): 1 2 3\n")
    assert read_rows(tmp_path) == [(20, [14, 17, 14]), (20, [15, 16, 14]), (19, [11, 12, 13])]
