"""world.sexp: the S-expression reader and writer, on hand-made input and on every trace."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from world.sexp import ProtocolError, SExpressionError, dumps, dumps_all, parse

TRACES = Path(__file__).resolve().parents[2] / "shared" / "reference" / "rcssserver3d-traces"


def _trace_messages() -> list[str]:
    """Every message the real server sent in the traces (agent and monitor ports)."""
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")
    messages = [path.read_text() for path in sorted(TRACES.glob("0[1-9]*.txt"))]
    for path in sorted(TRACES.glob("raw_*.jsonl")):
        messages += [json.loads(line)["msg"] for line in path.read_text().splitlines()]
    return messages


def test_parse_keeps_structure_and_atoms_as_strings() -> None:
    assert parse("(time (now 5.22))(GS (sl 0) (t -0.00))") == [
        ["time", ["now", "5.22"]],
        ["GS", ["sl", "0"], ["t", "-0.00"]],
    ]


def test_parse_accepts_bytes_any_whitespace_and_empty_lists() -> None:
    assert parse(b" (a\t(b\n c) ()) \r\n(d)") == [["a", ["b", "c"], []], ["d"]]
    assert parse("") == []


def test_parse_deep_nesting() -> None:
    assert parse("(a (b (c (d (e 1)))))") == [["a", ["b", ["c", ["d", ["e", "1"]]]]]]


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("(a (b 1)", "never closed"),
        ("(a))", "unexpected '\\)'"),
        (")(", "unexpected '\\)'"),
        ("(a) junk (b)", "garbage"),
        (b"(a \xff)", "not ASCII"),
    ],
)
def test_parse_rejects_bad_text_with_a_clear_message(text: str | bytes, words: str) -> None:
    with pytest.raises(SExpressionError, match=words):
        parse(text)


def test_errors_are_value_errors() -> None:
    assert issubclass(SExpressionError, ProtocolError)
    assert issubclass(SExpressionError, ValueError)


def test_dumps_writes_single_spaces_and_dumps_all_concatenates() -> None:
    assert dumps(["HJ", ["n", "hj1"], ["ax", "1.72"]]) == "(HJ (n hj1) (ax 1.72))"
    assert dumps("atom") == "atom"
    assert dumps([]) == "()"
    assert dumps_all([["syn"], ["he1", "0.5"]]) == "(syn)(he1 0.5)"


@pytest.mark.parametrize("bad", ["", "a b", "a(", ")"])
def test_dumps_refuses_atoms_that_would_not_read_back(bad: str) -> None:
    with pytest.raises(SExpressionError, match="cannot write atom"):
        dumps(["say", bad])


def test_dumps_refuses_other_types_and_top_level_atoms() -> None:
    with pytest.raises(SExpressionError, match="int"):
        dumps(["x", 1])  # type: ignore[list-item]
    with pytest.raises(SExpressionError, match="top-level"):
        dumps_all(["x"])


def test_every_trace_message_parses_and_round_trips() -> None:
    messages = _trace_messages()
    assert len(messages) > 400
    for message in messages:
        exprs = parse(message)
        assert exprs, message[:80]
        assert parse(dumps_all(exprs)) == exprs


def test_big_monitor_message_structure() -> None:
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")
    exprs = parse((TRACES / "07b_monitor_full_state_with_agent.txt").read_text())
    header, rsg, tree = exprs[:3]
    assert ["FieldLength", "30"] in header
    assert rsg == ["RSG", "0", "1"]
    assert tree[0][0] == "nd"


def test_canonical_agent_messages_are_written_back_byte_for_byte() -> None:
    # the agent messages use the writer's own spacing, except that perceptors are not
    # separated; the monitor ones are not canonical, so only structure is compared there
    if not TRACES.is_dir():
        pytest.skip(f"reference traces not found at {TRACES}")
    message = (TRACES / "01_first_msg_after_scene_type0.txt").read_text()
    assert dumps_all(parse(message)) == message


_ATOMS = st.text(
    alphabet=st.characters(min_codepoint=33, max_codepoint=126, blacklist_characters="()"),
    min_size=1,
    max_size=8,
)
_TREES = st.recursive(_ATOMS, lambda children: st.lists(children, max_size=5), max_leaves=30)


@given(st.lists(st.lists(_TREES, max_size=5), max_size=5))
def test_random_trees_round_trip(exprs: list) -> None:
    assert parse(dumps_all(exprs)) == exprs
    assert parse(dumps_all(exprs).encode()) == exprs
