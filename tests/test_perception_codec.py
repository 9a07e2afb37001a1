"""world.perception parse/write: byte-exact against every recorded real-server perception."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from world.field_geometry import LANDMARKS
from world.perception import (
    ForceResistance,
    GameState,
    Heard,
    Perception,
    Polar,
    ProtocolError,
    SeenPlayer,
    Vision,
    parse_perception,
    write_perception,
)

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"
AGENT_FILES = ("01", "02", "03", "04", "05", "06", "09")


def _require_traces() -> None:
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")


def _trace(prefix: str) -> str:
    _require_traces()
    (path,) = TRACES.glob(f"{prefix}_*.txt")
    return path.read_text()


def _agent_messages() -> list[str]:
    """Every perception the real server sent: the single-message files, the raw agent runs
    and the fidelity runs."""
    _require_traces()
    messages = [_trace(prefix) for prefix in AGENT_FILES]
    for path in sorted(TRACES.glob("raw_agent_*.jsonl")):
        messages += [json.loads(line)["msg"] for line in path.read_text().splitlines()]
    for path in sorted(TRACES.glob("fidelity/*.jsonl")):
        records = [json.loads(line) for line in path.read_text().splitlines()]
        messages += [r["perc"] for r in records if r.get("perc")]
    return messages


# ------------------------------------------------------------------ against the real server
def test_every_trace_perception_is_written_back_byte_for_byte() -> None:
    messages = _agent_messages()
    assert len(messages) > 1000
    for message in messages:
        assert write_perception(parse_perception(message)) == message.encode(), message[:120]
        assert write_perception(parse_perception(message.encode())) == message.encode()


def test_other_spacing_reads_the_same() -> None:
    """The general reader (taken for any non-canonical layout) agrees with the fast path."""
    for message in _agent_messages()[::7]:
        spaced = message.replace(")(", ") (").replace(" ", "\n  ")
        assert parse_perception(spaced) == parse_perception(message)


def test_see_message_values() -> None:
    p = parse_perception(_trace("03"))
    assert p.time == pytest.approx(5.22)
    assert p.game_state == GameState(0.0, "BeforeKickOff", 0, 0, None, None)
    assert p.gyro == (-0.25, -0.77, -0.57)
    assert p.accelerometer == (0.01, -0.0, 0.01)
    assert list(p.joints)[:3] == ["hj1", "hj2", "raj1"]
    assert len(p.joints) == 22
    assert p.joints["hj1"] == 1.72
    assert p.joints["llj4"] == -3.44
    assert p.force_resistance["rf"] == ForceResistance(
        "rf", (-0.0, -0.08, -0.01), (-0.43, -0.59, 119.04)
    )
    assert list(p.force_resistance) == ["rf", "lf"]
    vision = p.vision
    assert vision is not None
    assert list(vision.landmarks) == ["G2R", "G1R", "F1R", "F2R"]
    assert vision.landmarks["G2R"] == Polar(18.01, -2.71, 0.69)
    assert vision.ball == Polar(3.02, 1.07, -9.53)
    assert vision.players == [
        SeenPlayer(
            "Probe",
            1,
            {"rlowerarm": Polar(0.19, -38.51, -21.53), "llowerarm": Polar(0.19, 33.19, -21.77)},
        )
    ]
    assert len(vision.lines) == 17
    assert vision.lines[0] == (Polar(5.87, 59.94, -5.34), Polar(6.06, -59.78, -5.04))
    assert vision.players_before_landmarks == 0


def test_negative_zero_is_kept() -> None:
    p = parse_perception(_trace("03"))
    assert math.copysign(1.0, p.accelerometer[1]) == -1.0
    assert math.copysign(1.0, p.joints["raj1"]) == -1.0
    assert math.copysign(1.0, p.joints["raj2"]) == 1.0


def test_unum_and_team_message() -> None:
    gs = parse_perception(_trace("02")).game_state
    assert (gs.unum, gs.team) == (1, "left")
    assert parse_perception(_trace("02")).vision is None


def test_hear_self() -> None:
    p = parse_perception(_trace("04"))
    assert p.heard == [Heard("Probe", 0.0, "self", "probe1")]


def test_type4_toes() -> None:
    p = parse_perception(_trace("06"))
    assert list(p.joints)[-8:] == ["rlj7", "llj1", "llj2", "llj3", "llj4", "llj5", "llj6", "llj7"]
    assert list(p.force_resistance) == ["rf", "rf1", "lf", "lf1"]
    assert p.force_resistance["lf1"].force == (-0.25, -1.70, 79.08)


def test_other_team_player_parts() -> None:
    vision = parse_perception(_trace("09")).vision
    assert vision is not None
    beta = vision.players[1]
    assert (beta.team, beta.unum) == ("Beta", 9)
    assert list(beta.parts) == ["head", "rlowerarm", "llowerarm", "rfoot", "lfoot"]


def test_players_written_before_landmarks_are_recorded() -> None:
    """The real server sometimes writes the robot group before the field objects."""
    _require_traces()
    lines = (TRACES / "raw_agent_t0.jsonl").read_text().splitlines()
    message = next(
        m for m in (json.loads(line)["msg"] for line in lines) if "(See (P " in m and "(B " in m
    )
    vision = parse_perception(message).vision
    assert vision is not None and vision.landmarks
    assert vision.players_before_landmarks == 1
    assert b"(See (P (team Probe)" in write_perception(parse_perception(message))


# ------------------------------------------------------------------ robustness
def test_unknown_perceptors_and_see_objects_are_ignored() -> None:
    message = (
        "(time (now 1.00))(FOO (bar 1) (baz (qux 2)))(GS (sl 1) (sr 2) (t 3.00) (pm PlayOn) "
        "(new 5))(See (F1L (pol 1.00 2.00 3.00)) (mypos 1 2 3) (X9 (pol 1 2 3)))(TCH n 1)"
        "(HJ (n hj1) (ax 4.00))"
    )
    p = parse_perception(message)
    assert p.game_state == GameState(3.0, "PlayOn", 1, 2)
    assert p.joints == {"hj1": 4.0}
    assert p.vision == Vision(landmarks={"F1L": Polar(1.0, 2.0, 3.0)})


def test_old_hear_without_team_and_hear_from_a_direction() -> None:
    p = parse_perception("(hear 12.30 -45.50 hello)(hear Alpha 1.00 self x)")
    assert p.heard == [Heard("", 12.3, -45.5, "hello"), Heard("Alpha", 1.0, "self", "x")]
    assert write_perception(p).startswith(
        b"(time (now 0.00))(GS (sl 0) (sr 0) (t 0.00) (pm BeforeKickOff))"
        b"(hear 12.30 -45.50 hello)(hear Alpha 1.00 self x)(GYR"
    )


@pytest.mark.parametrize(
    ("message", "words"),
    [
        ("(time (now 5.22)", "unbalanced"),
        ("(HJ (n hj1) (ax abc))", "HJ.*'abc'"),
        ("(HJ (n hj1))", "HJ"),
        ("(GYR (n torso) (rt 1 2))", "GYR.*rt"),
        ("(FRP (n lf) (c 1 2 3))", "FRP"),
        ("(See (B (pol 1 2)))", "See.*pol"),
        ("(See (L (pol 1 2 3)))", "See.*L"),
        ("(See (P (team A) (id 1) (team (pol 1 2 3))))", "See.*name"),
        ("(See (P (team A) (id x)))", "See.*integer"),
        ("(GS (sl x))", "GS.*integer"),
        ("(hear a)", "hear"),
        ("((time))", "without a name"),
        ("time", "garbage"),
    ],
)
def test_malformed_messages_raise_protocol_error(message: str, words: str) -> None:
    with pytest.raises(ProtocolError, match=words):
        parse_perception(message)


def test_protocol_error_is_a_value_error() -> None:
    with pytest.raises(ValueError):
        parse_perception(b"(HJ (n hj1) (ax nope))")


# ------------------------------------------------------------------ writer details
def test_write_orders_like_the_server() -> None:
    p = Perception(
        time=1.0,
        game_state=GameState(unum=3, team="right"),
        joints={"hj1": 0.0, "rlj5": 1.0, "rlj6": 2.0, "hj2": -0.0, "llj6": 3.0},
        force_resistance={
            "lf": ForceResistance("lf", (0, 0, 0), (0, 0, 1)),
            "rf": ForceResistance("rf", (0, 0, 0), (0, 0, 2)),
            "rf1": ForceResistance("rf1", (0, 0, 0), (0, 0, 3)),
        },
        vision=Vision(),
    )
    assert write_perception(p) == (
        b"(time (now 1.00))(GS (unum 3) (team right) (sl 0) (sr 0) (t 0.00) (pm BeforeKickOff))"
        b"(GYR (n torso) (rt 0.00 0.00 0.00))(ACC (n torso) (a 0.00 0.00 0.00))"
        b"(HJ (n hj1) (ax 0.00))(HJ (n hj2) (ax -0.00))(See)"
        b"(HJ (n rlj5) (ax 1.00))"
        b"(FRP (n rf) (c 0.00 0.00 0.00) (f 0.00 0.00 2.00))(HJ (n rlj6) (ax 2.00))"
        b"(FRP (n lf) (c 0.00 0.00 0.00) (f 0.00 0.00 1.00))(HJ (n llj6) (ax 3.00))"
        b"(FRP (n rf1) (c 0.00 0.00 0.00) (f 0.00 0.00 3.00))"
    )


# ------------------------------------------------------------------ property tests
_NAMES = st.text(
    alphabet="abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.",
    min_size=1,
    max_size=10,
)
_NUMBERS = st.floats(min_value=-1000, max_value=1000, allow_nan=False).map(lambda x: round(x, 2))
_VECTORS = st.tuples(_NUMBERS, _NUMBERS, _NUMBERS)
_POLARS = st.builds(Polar, _NUMBERS, _NUMBERS, _NUMBERS)
_JOINT_NAMES = [
    "hj1", "hj2", *(f"raj{i}" for i in range(1, 5)), *(f"laj{i}" for i in range(1, 5)),
    *(f"rlj{i}" for i in range(1, 8)), *(f"llj{i}" for i in range(1, 8)),
]  # fmt: skip


@st.composite
def _players(draw: st.DrawFn) -> SeenPlayer:
    parts = draw(
        st.lists(st.sampled_from(["head", "rlowerarm", "llowerarm", "rfoot", "lfoot"]), unique=True)
    )
    return SeenPlayer(
        draw(_NAMES), draw(st.integers(0, 99)), {part: draw(_POLARS) for part in parts}
    )


@st.composite
def _visions(draw: st.DrawFn) -> Vision:
    names = draw(st.lists(st.sampled_from(sorted(LANDMARKS)), unique=True))
    landmarks = {name: draw(_POLARS) for name in names}
    ball = draw(st.none() | _POLARS)
    players = draw(st.lists(_players(), max_size=3))
    split = draw(st.integers(0, len(players))) if (landmarks or ball) else 0
    lines = draw(st.lists(st.tuples(_POLARS, _POLARS), max_size=5))
    return Vision(landmarks, ball, players, lines, split)


@st.composite
def _perceptions(draw: st.DrawFn) -> Perception:
    joint_count = draw(st.integers(0, len(_JOINT_NAMES)))
    joints = {name: draw(_NUMBERS) for name in _JOINT_NAMES[:joint_count]}
    feet = draw(st.lists(st.sampled_from(["lf", "rf", "lf1", "rf1"]), unique=True))
    heard = draw(
        st.lists(st.builds(Heard, _NAMES, _NUMBERS, st.just("self") | _NUMBERS, _NAMES), max_size=2)
    )
    return Perception(
        time=draw(_NUMBERS),
        game_state=GameState(
            draw(_NUMBERS),
            draw(_NAMES),
            draw(st.integers(0, 30)),
            draw(st.integers(0, 30)),
            draw(st.none() | st.integers(0, 11)),
            draw(st.none() | st.sampled_from(["left", "right"])),
        ),
        gyro=draw(_VECTORS),
        accelerometer=draw(_VECTORS),
        joints=joints,
        force_resistance={f: ForceResistance(f, draw(_VECTORS), draw(_VECTORS)) for f in feet},
        vision=draw(st.none() | _visions()),
        heard=heard,
    )


@settings(max_examples=200, deadline=None)
@given(_perceptions())
def test_random_perceptions_survive_write_and_parse(p: Perception) -> None:
    message = write_perception(p)
    back = parse_perception(message)
    assert back == p
    assert list(back.joints) == list(p.joints)
    assert write_perception(back) == message
