"""Stand-in vs real rcssserver3d on the recorded motions: prints one ``name: value`` per figure.

Run: ``.venv/bin/python benchmarks/fidelity.py [--substeps N]``
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sim.fidelity import load_recording, replay

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"
MOTIONS = ("stand_t0", "crouch_t0", "crouch_t4", "fall_t0", "swing_t0")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--substeps", type=int, default=2)
    args = parser.parse_args()
    folder = TRACES / "fidelity"
    if not folder.exists():
        raise SystemExit(f"recordings missing: {folder}")
    print(f"substeps: {args.substeps}")
    for motion in MOTIONS:
        comparison = replay(load_recording(folder / f"{motion}.jsonl"), substeps=args.substeps)
        for name, value in comparison.figures().items():
            print(f"{name}: {value:.4f}")


if __name__ == "__main__":
    main()
