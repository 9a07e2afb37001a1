"""Message framing of the SimSpark TCP protocol.

Both server ports (agents on 3100, monitors on 3200) send every message, in both directions,
as a 4-byte big-endian unsigned length followed by that many payload bytes. TCP delivers a
byte stream, so a receiver has to put frames back together from arbitrary chunks; that is
what :class:`FrameDecoder` does.
"""

from __future__ import annotations

HEADER_SIZE = 4
#: the largest length a 4-byte unsigned prefix can express
MAX_FRAME_LENGTH = (1 << 32) - 1


class FrameError(ValueError):
    """A frame that cannot be written, or a length prefix the receiver refuses."""


def frame(payload: bytes) -> bytes:
    """Prefix ``payload`` with its length as 4 big-endian bytes."""
    length = len(payload)
    if length > MAX_FRAME_LENGTH:
        raise FrameError(
            f"payload of {length} bytes does not fit a 4-byte length prefix "
            f"(at most {MAX_FRAME_LENGTH})"
        )
    return length.to_bytes(HEADER_SIZE, "big") + bytes(payload)


class FrameDecoder:
    """Splits a received byte stream back into payloads.

    ``feed`` takes whatever chunk the socket returned and gives back the payloads completed
    by it, keeping a partial frame for the next call. A length prefix above ``max_length``
    raises :class:`FrameError`: it usually means the stream is out of step (or the peer is not
    speaking this protocol), and trusting it would mean buffering up to 4 GiB. The stream
    cannot be resynchronised after that, so every later ``feed`` raises again; drop the
    connection.
    """

    def __init__(self, max_length: int = 1 << 20) -> None:
        if max_length < 0:
            raise ValueError(f"max_length must be >= 0, got {max_length}")
        self.max_length = max_length
        self._buffer = bytearray()
        self._error: FrameError | None = None

    @property
    def pending(self) -> int:
        """Bytes held of a frame not yet complete (its prefix included)."""
        return len(self._buffer)

    def feed(self, data: bytes) -> list[bytes]:
        """Add received bytes; return the payloads now complete, oldest first."""
        if self._error is not None:
            raise self._error
        buffer = self._buffer
        buffer += data
        payloads = []
        start = 0
        end = len(buffer)
        while end - start >= HEADER_SIZE:
            length = int.from_bytes(buffer[start : start + HEADER_SIZE], "big")
            if length > self.max_length:
                del buffer[:start]
                self._error = FrameError(
                    f"frame length {length} exceeds the limit of {self.max_length} bytes "
                    "(stream out of step or not this protocol)"
                )
                raise self._error
            stop = start + HEADER_SIZE + length
            if stop > end:
                break
            payloads.append(bytes(buffer[start + HEADER_SIZE : stop]))
            start = stop
        if start:
            del buffer[:start]
        return payloads
