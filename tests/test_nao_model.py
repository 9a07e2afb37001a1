"""The NAO tables against the published facts (``shared/reference/nao-model-facts.md``).

The facts file is parsed here, so a transcription slip or a wrong type derivation fails loudly.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from world.nao_model import ROBOT_TYPES, robot_spec

FACTS = Path(__file__).resolve().parents[2] / "shared" / "reference" / "nao-model-facts.md"
_NUM = r"[+-]?\d+(?:\.\d+)?"


@pytest.fixture(scope="module")
def facts() -> str:
    if not FACTS.exists():
        pytest.skip(f"reference facts missing: {FACTS} (the shared/ folder beside the repo)")
    return FACTS.read_text()


def _section(text: str, heading: str) -> list[list[str]]:
    """Rows (cells) of the first markdown table after ``heading``."""
    start = text.index(heading)
    rows = []
    for line in text[start:].splitlines()[1:]:
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not set(cells[0]) <= {"-"}:
                rows.append(cells)
        elif rows:
            break
    return rows[1:]  # drop the header row


def _vec(cell: str) -> tuple[float, ...]:
    return tuple(float(v) for v in re.findall(_NUM, cell))


@pytest.mark.parametrize(
    ("robot_type", "heading"), [(0, "## Bodies, type 0"), (4, "## Bodies, type 4")]
)
def test_bodies_match_facts(facts: str, robot_type: int, heading: str) -> None:
    spec = robot_spec(robot_type)
    rows = [r for r in _section(facts, heading) if not r[0].startswith("**")]
    assert [r[0] for r in rows] == [b.name for b in spec.bodies]
    for name, shape, size, mass, centre, collider in rows:
        body = spec.body(name)
        assert body.shape == shape
        assert body.size == pytest.approx(_vec(size), abs=1e-6)
        assert body.mass == pytest.approx(float(mass), abs=1e-6)
        assert body.centre == pytest.approx(_vec(centre), abs=1e-4)
        assert body.collider == (collider == "yes")


@pytest.mark.parametrize(
    ("robot_type", "heading"), [(0, "## Joints, type 0"), (4, "## Joints, type 4")]
)
def test_joints_match_facts(facts: str, robot_type: int, heading: str) -> None:
    spec = robot_spec(robot_type)
    rows = _section(facts, heading)
    by_name = {r[0]: r for r in rows}
    assert set(by_name) == set(spec.perceptor_names)
    for joint in spec.joints:
        _, eff, child, parent, anchor, axis, lo, hi, speed = by_name[joint.perceptor]
        assert (joint.effector, joint.child, joint.parent) == (eff, child, parent)
        assert joint.anchor == pytest.approx(_vec(anchor), abs=1e-4)
        assert joint.axis == pytest.approx(_vec(axis), abs=1e-4)
        assert (joint.min_deg, joint.max_deg) == (float(lo), float(hi))
        assert joint.max_speed == pytest.approx(float(speed), abs=1e-4)


def test_hj_order_is_the_servers() -> None:
    legs = [f"{s}lj{i}" for s in "rl" for i in range(1, 7)]
    arms = [f"{s}aj{i}" for s in "rl" for i in range(1, 5)]
    assert robot_spec(0).perceptor_names == ("hj1", "hj2", *arms, *legs)
    toes = robot_spec(4).perceptor_names
    assert toes.index("rlj7") == toes.index("rlj6") + 1
    assert toes[-1] == "llj7"
    assert len(toes) == 24


@pytest.mark.parametrize("robot_type", [1, 3])
def test_derived_positions_match_facts(facts: str, robot_type: int) -> None:
    line = next(ln for ln in facts.splitlines() if ln.startswith(f"- type {robot_type}:"))
    entries = re.findall(rf"(\w+) \(({_NUM}), ({_NUM}), ({_NUM})\)", line)
    assert len(entries) >= 6
    spec = robot_spec(robot_type)
    for name, x, y, z in entries:
        right = spec.body(name).centre
        left = spec.body("l" + name[1:]).centre
        assert right == pytest.approx((float(x), float(y), float(z)), abs=1e-4)
        assert left == pytest.approx((-float(x), float(y), float(z)), abs=1e-4)


def test_hetero_table(facts: str) -> None:
    for row in _section(facts, "## Hetero types 0-4"):
        spec = robot_spec(int(row[0]))
        assert spec.body("rhip1").centre[0] == pytest.approx(float(row[1]), abs=1e-6)
        assert spec.joint("rlj5").max_speed == pytest.approx(float(row[6]))
        assert spec.joint("llj6").max_speed == pytest.approx(float(row[7]))
        assert spec.has_toes == row[8].startswith("yes")
        assert spec.sole_height() == pytest.approx(float(row[9]), abs=1e-6)


@pytest.mark.parametrize("robot_type", ROBOT_TYPES)
def test_every_type_is_complete(robot_type: int) -> None:
    spec = robot_spec(robot_type)
    assert spec.total_mass == pytest.approx(4.6071, abs=1e-6)
    names = {b.name for b in spec.bodies}
    for joint in spec.joints:
        assert joint.child in names
        assert joint.parent in names
        assert joint.min_deg < joint.max_deg
    children = [j.child for j in spec.joints]
    assert sorted(children) == sorted(names - {"torso"})  # a tree rooted at the torso
    assert len(set(spec.effector_names)) == len(spec.joints)


def test_foot_sensors() -> None:
    assert robot_spec(0).foot_sensors == {"lf": "lfoot", "rf": "rfoot"}
    assert robot_spec(4).foot_sensors["rf1"] == "rtoe"


@pytest.mark.parametrize("bad", [-1, 5, 7, True])
def test_invalid_type_lists_valid_ones(bad: int) -> None:
    with pytest.raises(ValueError, match="0, 1, 2, 3, 4"):
        robot_spec(bad)
