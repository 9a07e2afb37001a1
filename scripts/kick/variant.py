"""Write a copy of the packaged kicks.yaml with some frame joints changed (kick candidates for
``benchmarks/kick.py --kicks FILE`` and ``scripts/kick/sweep.py --kicks FILE``).

Run: ``python scripts/kick/variant.py OUT kick_right_aligned:3:llj4=-100 ...``: entry, frame
index, joint=value (``duration``/``hold`` change the frame's timing)."""

from __future__ import annotations

import sys
from pathlib import Path

import yaml

from behaviors.kick import KICKS_FILE


def main() -> None:
    out, *changes = sys.argv[1:]
    data = yaml.safe_load(KICKS_FILE.read_text())
    for change in changes:
        where, value = change.split("=")
        entry, index, key = where.split(":")
        frame = dict(data[entry]["frames"][int(index)])
        if key in ("duration", "hold"):
            frame[key] = float(value)
        else:
            frame["joints"] = {**frame.get("joints", {}), key: float(value)}
        frames = list(data[entry]["frames"])
        frames[int(index)] = frame
        data[entry] = {**data[entry], "frames": frames}
    Path(out).write_text(yaml.safe_dump(data, sort_keys=False, width=100))


if __name__ == "__main__":
    main()
