"""A playing agent needs neither pybullet nor torch: importing its packages must not load them."""

from __future__ import annotations

import subprocess
import sys

import pytest


@pytest.mark.parametrize(
    "module",
    ["world", "world.perception", "world.effectors", "world.sexp", "world.nao_model",
     "world.field_geometry", "agent", "agent.cli", "agent.transport", "agent.demo", "behaviors"],
)  # fmt: skip
def test_light_packages_do_not_import_pybullet_or_torch(module):
    code = (
        f"import sys, {module}; "
        "heavy = [m for m in ('pybullet', 'torch') if m in sys.modules]; "
        "print(','.join(heavy))"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "", f"{module} imports {result.stdout.strip()}"
