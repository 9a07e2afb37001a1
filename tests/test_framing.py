"""world.framing: 4-byte big-endian length prefix, reassembly from arbitrary TCP chunks."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from world.framing import FrameDecoder, FrameError, frame


def test_frame_prefixes_big_endian_length() -> None:
    assert frame(b"(syn)") == b"\x00\x00\x00\x05(syn)"
    assert frame(b"") == b"\x00\x00\x00\x00"
    assert frame(b"x" * 300)[:4] == b"\x00\x00\x01\x2c"


def test_decoder_returns_complete_payloads_in_order() -> None:
    decoder = FrameDecoder()
    stream = frame(b"(a)") + frame(b"") + frame(b"(bb)")
    assert decoder.feed(stream) == [b"(a)", b"", b"(bb)"]
    assert decoder.pending == 0


def test_decoder_keeps_partial_frames_across_calls() -> None:
    decoder = FrameDecoder()
    data = frame(b"(hello)") + frame(b"(world)")
    assert decoder.feed(data[:2]) == []  # half a prefix
    assert decoder.pending == 2
    assert decoder.feed(data[2:9]) == []  # prefix and part of the payload
    assert decoder.pending == 9
    assert decoder.feed(data[9:14]) == [b"(hello)"]
    assert decoder.pending == 3
    assert decoder.feed(data[14:]) == [b"(world)"]
    assert decoder.pending == 0


def test_decoder_byte_by_byte() -> None:
    decoder = FrameDecoder()
    out: list[bytes] = []
    for byte in frame(b"(time (now 1.00))") * 3:
        out += decoder.feed(bytes([byte]))
    assert out == [b"(time (now 1.00))"] * 3


def test_oversized_prefix_raises_naming_length_and_limit() -> None:
    decoder = FrameDecoder(max_length=100)
    assert decoder.feed(frame(b"x" * 100)) == [b"x" * 100]
    with pytest.raises(FrameError, match=r"length 101 exceeds the limit of 100"):
        decoder.feed(frame(b"x" * 101))
    # the stream is out of step for good: later data cannot be trusted
    with pytest.raises(FrameError):
        decoder.feed(frame(b"ok"))


def test_oversized_prefix_is_caught_before_its_payload_arrives() -> None:
    decoder = FrameDecoder()
    with pytest.raises(FrameError, match=str(1 << 20)):
        decoder.feed(b"GET / HTTP/1.1\r\n")  # a peer that does not speak this protocol


def test_frame_error_is_a_value_error() -> None:
    assert issubclass(FrameError, ValueError)
    with pytest.raises(ValueError):
        FrameDecoder(max_length=-1)


@given(
    st.lists(st.binary(max_size=300), max_size=8),
    st.lists(st.integers(min_value=1, max_value=50), min_size=1, max_size=20),
)
def test_any_chunking_gives_back_the_same_payloads(payloads: list[bytes], cuts: list[int]) -> None:
    stream = b"".join(frame(p) for p in payloads)
    decoder = FrameDecoder()
    out: list[bytes] = []
    position, k = 0, 0
    while position < len(stream):
        size = cuts[k % len(cuts)]
        out += decoder.feed(stream[position : position + size])
        position += size
        k += 1
    assert out == payloads
    assert decoder.pending == 0
