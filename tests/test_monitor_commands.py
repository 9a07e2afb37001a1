"""Trainer command parsing: the commands a real client sent, every form the real parser knows,
and malformed input."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim.monitor import (
    DropBall,
    KickOff,
    KillAgent,
    KillSelectedAgent,
    KillSimulation,
    MoveAgent,
    MoveBall,
    ReposAgent,
    ReposSelectedAgent,
    RequestAck,
    RequestFullState,
    ResetSelection,
    SelectAgent,
    SelectNextAgent,
    SetPlayMode,
    SetScore,
    SetTime,
    TrainerCommand,
    parse_trainer_commands,
)
from world.play_modes import PLAY_MODES

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"


def _one(text: str) -> TrainerCommand:
    commands, errors = parse_trainer_commands(text.encode())
    assert errors == []
    assert len(commands) == 1
    return commands[0]


def _error(text: str) -> str:
    commands, errors = parse_trainer_commands(text.encode())
    assert commands == [], commands
    assert len(errors) == 1, errors
    return errors[0]


def test_commands_sent_in_the_recorded_run() -> None:
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")
    lines = (TRACES / "sent_agent_t1.jsonl").read_text().splitlines()
    sent = [json.loads(line)["msg"] for line in lines if line.strip()]
    monitor = [m for m, line in zip(sent, lines, strict=True) if '"mon>"' in line]
    parsed = [parse_trainer_commands(m.encode()) for m in monitor]
    assert all(errors == [] for _, errors in parsed)
    assert [commands for commands, _ in parsed] == [
        [SetPlayMode("PlayOn")],
        [MoveBall((1.0, 0.0, 0.042), (0.0, 0.0, 0.0))],
        [MoveAgent(1, "Left", (-1.0, 0.0, 0.5), 0.0)],
        [MoveBall((-1.0, 2.0, 0.042), (0.0, 0.0, 0.0))],
    ]


def test_every_play_mode_is_accepted() -> None:
    for mode in PLAY_MODES:
        assert _one(f"(playMode {mode})") == SetPlayMode(mode)


def test_ball_parts_are_optional() -> None:
    assert _one("(ball (pos 1 2 0.042))") == MoveBall((1.0, 2.0, 0.042), None)
    assert _one("(ball (vel 3 0 0))") == MoveBall(None, (3.0, 0.0, 0.0))
    assert _one("(ball (vel 3 0 0) (pos 1 2 3))") == MoveBall((1.0, 2.0, 3.0), (3.0, 0.0, 0.0))


def test_agent_forms() -> None:
    assert _one("(agent (team Right) (unum 4) (pos 1 2 0.4))") == MoveAgent(
        4, "Right", (1.0, 2.0, 0.4)
    )
    assert _one("(agent (unum 2) (team Left) (rot 0 0 90))") == MoveAgent(
        2, "Left", euler_deg=(0.0, 0.0, 90.0)
    )
    # move wins over pos: the server applies move after pos
    both = _one("(agent (unum 2) (team Left) (move 3 4 0.5 -90) (pos 1 1 1))")
    assert both == MoveAgent(2, "Left", (3.0, 4.0, 0.5), -90.0)
    kept = _one("(agent (unum 9) (team Left) (battery 80) (temperature 40.5))")
    assert kept == MoveAgent(9, "Left", battery=80.0, temperature=40.5)
    assert _one("(agent)") == ResetSelection()


def test_the_other_commands_of_the_real_parser() -> None:
    cases = {
        "(kickOff Left)": KickOff("Left"),
        "(kickOff None)": KickOff("None"),
        "(dropBall)": DropBall(),
        "(reqfullstate)": RequestFullState(),
        "(getAck)": RequestAck(),
        "(killsim)": KillSimulation(),
        "(kill (unum 3) (team Right))": KillAgent(3, "Right"),
        "(kill)": KillSelectedAgent(),
        "(repos (unum 5) (team Left))": ReposAgent(5, "Left"),
        "(repos)": ReposSelectedAgent(),
        "(select (unum 1) (team Left))": SelectAgent(1, "Left"),
        "(select (unum -1))": ResetSelection(),
        "(select)": SelectNextAgent(),
        "(time 120.5)": SetTime(120.5),
        "(score (left 2) (right 0))": SetScore(2, 0),
        "(score (right 1) (left 3))": SetScore(3, 1),
    }
    for text, expected in cases.items():
        assert _one(text) == expected, text


def test_several_commands_in_one_message_keep_their_order() -> None:
    commands, errors = parse_trainer_commands(
        b"(playMode KickOff_Left)(ball (pos 0 0 0.042))(reqfullstate)"
    )
    assert errors == []
    assert commands == [
        SetPlayMode("KickOff_Left"),
        MoveBall((0.0, 0.0, 0.042)),
        RequestFullState(),
    ]


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("(playMode Halftime)", "unknown play mode 'Halftime'"),
        ("(playMode)", "expected one play mode name"),
        ("(playmode PlayOn)", "unknown trainer command 'playmode'"),
        ("(ball)", "give (pos x y z) and/or (vel x y z)"),
        ("(ball (pos 1 2))", "expected 3 numbers, got 2"),
        ("(ball (pos 1 two 3))", "'two' is not a number"),
        ("(ball (pos 1 nan 3))", "not a finite number"),
        ("(ball (poss 1 2 3))", "unknown part 'poss'"),
        ("(ball (pos 1 2 3) (pos 1 2 3))", "given twice"),
        ("(agent (unum 1) (move 1 2 3 4))", "give both (unum N) and (team Left|Right)"),
        ("(agent (move 1 2 3 4))", "give (unum N) (team Left|Right)"),
        ("(agent (unum 1) (team left) (move 1 2 3 4))", "team must be Left or Right"),
        ("(agent (unum 1.5) (team Left))", "'1.5' is not an integer"),
        ("(agent (unum 1) (team Left) (move 1 2 3))", "expected 4 numbers, got 3"),
        ("(kickOff Both)", "side must be Left, Right or None"),
        ("(dropBall now)", "takes no arguments"),
        ("(kill (unum 3))", "give both"),
        ("(time -1)", "cannot be negative"),
        ("(score (left 1))", "expected (score (left L) (right R))"),
        ("(score (left -1) (right 0))", "cannot be negative"),
        ("(select (team Left))", "give both"),
        ("((playMode) PlayOn)", "starts with its name"),
    ],
)
def test_malformed_commands_give_one_clear_error(text: str, needle: str) -> None:
    error = _error(text)
    assert needle in error
    assert error.startswith(text[:20])  # says which command


def test_good_commands_survive_bad_neighbours() -> None:
    commands, errors = parse_trainer_commands(
        b"(playMode PlayOn)(ball (pos x 0 0))(kickOff Right)(bogus 1)"
    )
    assert commands == [SetPlayMode("PlayOn"), KickOff("Right")]
    assert len(errors) == 2
    assert "ball" in errors[0] and "bogus" in errors[1]


def test_unreadable_messages() -> None:
    for payload in (b"(playMode PlayOn", b"playMode PlayOn", b"\xff\xfe"):
        commands, errors = parse_trainer_commands(payload)
        assert commands == []
        assert len(errors) == 1 and "unreadable trainer message" in errors[0]
    assert parse_trainer_commands(b"") == ([], [])


@settings(max_examples=200, deadline=None)
@given(st.binary(max_size=60))
def test_arbitrary_bytes_never_raise(payload: bytes) -> None:
    commands, errors = parse_trainer_commands(payload)
    assert all(isinstance(c, TrainerCommand) for c in commands)
    assert all(isinstance(e, str) and e for e in errors)


finite = st.floats(allow_nan=False, allow_infinity=False, width=32)


@settings(max_examples=100, deadline=None)
@given(finite, finite, finite, finite, st.integers(0, 11), st.sampled_from(["Left", "Right"]))
def test_move_round_trips(x: float, y: float, z: float, deg: float, unum: int, team: str) -> None:
    text = f"(agent (unum {unum}) (team {team}) (move {x!r} {y!r} {z!r} {deg!r}))"
    assert _one(text) == MoveAgent(unum, team, (x, y, z), deg)  # type: ignore[arg-type]
