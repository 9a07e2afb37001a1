"""Write a copy of the packaged kicks.yaml with a landing catch (``behaviors/kick_recovery.py``)
on the kicks that ``basic_kick`` plays (the ``*_aligned`` motions and their long versions).

Run: ``python scripts/kick/catch_variant.py OUT [field=value ...]`` (fields of
:class:`behaviors.kick_recovery.CatchParams`; none: its defaults), then screen the file with
``scripts/kick/kick_bank.py --variants cand:OUT:1.5`` or ``scripts/kick/sweep.py --kicks OUT``."""

from __future__ import annotations

import sys
from pathlib import Path

import yaml

from behaviors.kick import KICKS_FILE, load_kicks

ALIGNED = (
    "kick_left_aligned",
    "kick_left_aligned_long",
    "kick_right_aligned",
    "kick_right_aligned_long",
)


def main() -> None:
    out, *changes = sys.argv[1:]
    data = yaml.safe_load(KICKS_FILE.read_text())
    catch = {key: float(value) for key, value in (c.split("=") for c in changes)}
    for name in ALIGNED:
        data[name] = {**data[name], "catch": catch}
    Path(out).write_text(yaml.safe_dump(data, sort_keys=False, width=100))
    load_kicks(out)  # fails on unknown fields or bad values


if __name__ == "__main__":
    main()
