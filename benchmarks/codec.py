"""Speed of the perception codec on a full real-server message (with a See perceptor).

Prints ``parse_us: X`` and ``write_us: Y`` (median microseconds per call) for the trace
message ``03_see_flags_goals_ball_lines_ownarms_frp.txt``. Run: ``python benchmarks/codec.py``.
"""

from __future__ import annotations

import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[1]
if str(REPO_ROOT) not in sys.path:
    sys.path.insert(0, str(REPO_ROOT))

from world.perception import parse_perception, write_perception  # noqa: E402

TRACE = (
    REPO_ROOT.parent
    / "shared"
    / "reference"
    / "rcssserver3d-traces"
    / "03_see_flags_goals_ball_lines_ownarms_frp.txt"
)


def _message() -> bytes:
    return TRACE.read_bytes()


def _median_us(call: Callable[[], object], repeats: int, batch: int = 10) -> float:
    """Median over ``repeats`` timings; each timing averages ``batch`` calls so that the clock's
    resolution and the loop do not dominate a call of some tens of microseconds."""
    call()  # warm up caches and lazily compiled patterns
    samples = []
    for _ in range(max(1, repeats // batch)):
        start = time.perf_counter_ns()
        for _ in range(batch):
            call()
        samples.append((time.perf_counter_ns() - start) / batch / 1000.0)
    return statistics.median(samples)


def measure_parse_us(repeats: int = 2000) -> float:
    """Median microseconds of ``parse_perception`` on the benchmark message."""
    message = _message()
    return _median_us(lambda: parse_perception(message), repeats)


def measure_write_us(repeats: int = 2000) -> float:
    """Median microseconds of ``write_perception`` on the parsed benchmark message."""
    perception = parse_perception(_message())
    return _median_us(lambda: write_perception(perception), repeats)


def main() -> None:
    print(f"parse_us: {measure_parse_us():.1f}")
    print(f"write_us: {measure_write_us():.1f}")


if __name__ == "__main__":
    main()
