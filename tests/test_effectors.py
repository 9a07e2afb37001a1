"""world.effectors: what clients send, checked against the messages a real client sent."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from world import effectors as effectors_module
from world.effectors import (
    JOINT_EFFECTORS,
    EffectorMessage,
    effector_for_joint,
    joint_for_effector,
    parse_effectors,
    write_effectors,
)
from world.sexp import SExpressionError

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"


def _sent_agent_messages() -> list[str]:
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")
    messages = []
    for path in sorted(TRACES.glob("sent_agent_*.jsonl")):
        records = [json.loads(line) for line in path.read_text().splitlines()]
        messages += [r["msg"] for r in records if r["dir"] == ">"]
    return messages


def test_every_sent_agent_message_parses_without_errors_and_survives_writing() -> None:
    messages = _sent_agent_messages()
    assert len(messages) > 400
    for message in messages:
        parsed, errors = parse_effectors(message)
        assert errors == [], message
        assert parse_effectors(write_effectors(parsed)) == (parsed, [])


def test_sent_messages_read_as_expected() -> None:
    messages = set(_sent_agent_messages())
    assert "(scene rsg/agent/nao/nao_hetero.rsg 4)" in messages
    assert parse_effectors("(scene rsg/agent/nao/nao_hetero.rsg 4)")[0] == EffectorMessage(
        scene=("rsg/agent/nao/nao_hetero.rsg", 4)
    )
    assert "(init (unum 1)(teamname Probe))(syn)" in messages
    assert parse_effectors(b"(init (unum 1)(teamname Probe))(syn)")[0] == EffectorMessage(
        init=(1, "Probe"), syn=True
    )
    assert parse_effectors("(beam -3 0 0)(syn)")[0].beam == (-3.0, 0.0, 0.0)
    speeds = parse_effectors("(he1 0)(lle4 0)(say probe1)(syn)")[0]
    assert speeds == EffectorMessage(joint_speeds={"he1": 0.0, "lle4": 0.0}, say="probe1", syn=True)


@pytest.mark.parametrize(
    "message",
    [
        "(he1 0.5)(lle4 -1.0)(syn)",
        "(he1 -0.5)(lle4 1.0)(syn)",
        "(scene rsg/agent/nao/nao_hetero.rsg 0)",
        "(init (unum 2)(teamname Probe))(syn)",
    ],
)
def test_messages_in_short_float_format_are_written_back_byte_for_byte(message: str) -> None:
    assert message in _sent_agent_messages()
    assert write_effectors(parse_effectors(message)[0]) == message.encode()


def test_scene_without_type_means_type_0_and_init_without_unum_means_0() -> None:
    message, errors = parse_effectors("(scene rsg/agent/nao/nao.rsg)(init (teamname A))")
    assert errors == []
    assert message.scene == ("rsg/agent/nao/nao.rsg", 0)
    assert message.init == (0, "A")


def test_bad_items_are_reported_and_good_ones_kept() -> None:
    message, errors = parse_effectors(
        "(he1 0.5)(foo 1)(lle4 x)(beam 1 2)(rle3 2 3)(say a b)(init (unum 2))(rae2 -1)(syn)"
    )
    assert message == EffectorMessage(joint_speeds={"he1": 0.5, "rae2": -1.0}, syn=True)
    assert len(errors) == 6
    assert "unknown effector 'foo'" in errors[0]
    assert "lle4" in errors[1] and "'x'" in errors[1]
    assert "beam" in errors[2] and "3 value(s), got 2" in errors[2]
    assert "rle3" in errors[3]
    assert "say" in errors[4]
    assert "teamname" in errors[5]


def test_trainer_commands_are_not_agent_effectors() -> None:
    message, errors = parse_effectors("(playMode PlayOn)")
    assert message == EffectorMessage()
    assert errors == ["unknown effector 'playMode' in (playMode PlayOn)"]


def test_toe_effectors_are_accepted_by_the_codec() -> None:
    assert parse_effectors("(lle7 1)(rle7 -1)") == (
        EffectorMessage(joint_speeds={"lle7": 1.0, "rle7": -1.0}),
        [],
    )
    assert parse_effectors("(lle8 1)")[1] == ["unknown effector 'lle8' in (lle8 1)"]


def test_non_finite_speeds_are_refused() -> None:
    message, errors = parse_effectors("(he1 nan)(he2 inf)")
    assert message.joint_speeds == {}
    assert len(errors) == 2
    with pytest.raises(SExpressionError, match="non-finite"):
        write_effectors(EffectorMessage(joint_speeds={"he1": float("nan")}))


def test_unreadable_message_is_ignored_with_one_error() -> None:
    message, errors = parse_effectors("(he1 0.5")
    assert message == EffectorMessage()
    assert len(errors) == 1 and "never closed" in errors[0]


def test_write_refuses_names_that_would_change_the_message() -> None:
    with pytest.raises(SExpressionError):
        write_effectors(EffectorMessage(say="two words"))
    with pytest.raises(SExpressionError):
        write_effectors(EffectorMessage(init=(1, "a)b")))


def test_write_order_and_format() -> None:
    message = EffectorMessage(
        scene=("rsg/agent/nao/nao_hetero.rsg", 4),
        init=(7, "Team"),
        beam=(-3.0, 0.5, 90.0),
        joint_speeds={"lle4": -1.0, "he1": 0.25},
        say="hi",
        syn=True,
    )
    assert write_effectors(message) == (
        b"(scene rsg/agent/nao/nao_hetero.rsg 4)(init (unum 7)(teamname Team))"
        b"(beam -3.0 0.5 90.0)(lle4 -1.0)(he1 0.25)(say hi)(syn)"
    )


def test_joint_name_helpers() -> None:
    assert effector_for_joint("rlj3") == "rle3"
    assert joint_for_effector("rle3") == "rlj3"
    pairs = {"hj1": "he1", "raj4": "rae4", "laj2": "lae2", "llj7": "lle7"}
    for joint, effector in pairs.items():
        assert effector_for_joint(joint) == effector
        assert joint_for_effector(effector) == joint
    assert [effector_for_joint(joint_for_effector(e)) for e in JOINT_EFFECTORS] == list(
        JOINT_EFFECTORS
    )
    assert len(JOINT_EFFECTORS) == 24
    for bad in ("rle3", "xyz1", "hj", ""):
        with pytest.raises(ValueError, match="not a joint perceptor"):
            effector_for_joint(bad)
    with pytest.raises(ValueError, match="not a joint effector"):
        joint_for_effector("rlj3")


_NAMES = st.text(alphabet="abcdefghijklmnopqrstuvwxyz0123456789_./-", min_size=1, max_size=12)
_NUMBERS = st.floats(allow_nan=False, allow_infinity=False)


@given(
    st.none() | st.tuples(_NAMES, st.integers(0, 4)),
    st.none() | st.tuples(st.integers(0, 11), _NAMES),
    st.none() | st.tuples(_NUMBERS, _NUMBERS, _NUMBERS),
    st.dictionaries(st.sampled_from(JOINT_EFFECTORS), _NUMBERS),
    st.none() | _NAMES,
    st.booleans(),
)
def test_random_messages_survive_write_and_parse(scene, init, beam, speeds, say, syn) -> None:
    message = EffectorMessage(scene, init, beam, speeds, say, syn)
    parsed, errors = parse_effectors(write_effectors(message))
    assert errors == []
    assert parsed == message
    assert list(parsed.joint_speeds) == list(speeds)


_PIECES = st.sampled_from(
    ["(", ")", " ", "he1", "lle7", "rae4", "xx1", "say", "syn", "0.5", "-1e3", "nan", "x", "é"]
)


@given(st.lists(_PIECES, max_size=14).map("".join))
def test_the_fast_path_reads_every_message_as_the_general_reader_does(text: str) -> None:
    # the fast path takes messages of the common layout (joint speeds, say, syn); whatever it
    # takes must come out exactly as the tolerant general reader has it, errors included
    for payload in (text, text.encode("utf-8")):
        assert parse_effectors(payload) == effectors_module._parse_general(payload)


def test_the_fast_path_takes_the_common_messages():
    text = "(he1 0.5)(lle4 -1.0)(say nb7c42)(syn)"
    fast = effectors_module._parse_canonical(text)
    assert fast == parse_effectors(text)[0] and fast.say == "nb7c42" and fast.syn
    assert effectors_module._parse_canonical("(beam 1 2 3)(syn)") is None
    assert effectors_module._parse_canonical("(he1 x)(syn)") is None
