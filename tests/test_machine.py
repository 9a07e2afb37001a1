"""benchmarks/machine.py: the lines that say which machine a set of figures came from."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from benchmarks.machine import machine_figures, numpy_simd

ROOT = Path(__file__).resolve().parents[1]


def test_machine_figures_name_the_cpu_simd_and_versions():
    figures = machine_figures()
    assert set(figures) == {
        "machine_cpu",
        "machine_cores",
        "numpy_simd",
        "numpy_version",
        "pybullet_version",
        "python_version",
    }
    assert all(value.strip() for value in figures.values())
    assert figures["pybullet_version"] != "not installed"


def test_numpy_simd_follows_npy_disable_cpu_features():
    """Switching numpy's AVX-512 kernels off shows in the line (when the CPU had them)."""
    here = numpy_simd()
    env = dict(os.environ, NPY_DISABLE_CPU_FEATURES="X86_V4 AVX512_ICL AVX512_SPR")
    out = subprocess.run(
        [sys.executable, "benchmarks/machine.py"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    lines = dict(line.split(": ", 1) for line in out.splitlines())
    assert "AVX512" not in lines["numpy_simd"] and lines["numpy_simd"] != "X86_V4"
    if "AVX512" not in here and here != "X86_V4":
        assert lines["numpy_simd"] == here
