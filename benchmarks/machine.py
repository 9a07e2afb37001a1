"""What machine a set of figures came from: CPU, numpy's SIMD level, library versions.

Why: the simulation is chaotic, so the last bit of a sine decides which benchmark trial falls.
numpy picks its sin/cos kernels at run time by CPU (an AVX-512 machine rounds differently from an
AVX2 one), so the same checkout and the same seeds give other trials, and other figures, on
another CPU. Session 15 met this: on an AVX-512 EPYC two of the basic-kick test's three layouts
fell where earlier sessions' EPYCs without AVX-512 had kicked all three. Figures compare
only between runs with the same lines here; ``scripts/bench`` prints them first.

Run: ``.venv/bin/python benchmarks/machine.py``; prints ``machine_cpu``, ``machine_cores``,
``numpy_simd`` (the widest SIMD target numpy dispatches to here), ``numpy_version``,
``pybullet_version``, ``python_version``.
"""

from __future__ import annotations

import importlib.metadata
import os
import platform
from pathlib import Path

import numpy as np


def cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo`` on Linux, else what ``platform`` knows)."""
    cpuinfo = Path("/proc/cpuinfo")
    if cpuinfo.exists():
        for line in cpuinfo.read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return platform.processor() or platform.machine()


def numpy_simd() -> str:
    """The widest of numpy's run-time dispatch targets this CPU supports (and that
    ``NPY_DISABLE_CPU_FEATURES`` did not switch off), or its baseline when none is."""
    from numpy._core._multiarray_umath import (  # numpy >= 2: where numpy keeps them
        __cpu_baseline__,
        __cpu_dispatch__,
        __cpu_features__,
    )

    enabled = [target for target in __cpu_dispatch__ if __cpu_features__.get(target)]
    return enabled[-1] if enabled else (__cpu_baseline__[-1] if __cpu_baseline__ else "none")


def version(package: str) -> str:
    try:
        return importlib.metadata.version(package)
    except importlib.metadata.PackageNotFoundError:
        return "not installed"


def machine_figures() -> dict[str, str]:
    return {
        "machine_cpu": cpu_model(),
        "machine_cores": str(os.cpu_count()),
        "numpy_simd": numpy_simd(),
        "numpy_version": np.__version__,
        "pybullet_version": version("pybullet"),
        "python_version": platform.python_version(),
    }


def main() -> None:
    for name, value in machine_figures().items():
        print(f"{name}: {value}")


if __name__ == "__main__":
    main()
