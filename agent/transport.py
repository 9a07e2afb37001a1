"""Transports that carry wire-format bytes between an agent and a server.

The agent speaks bytes; how they travel is the transport's business. :class:`TcpTransport`
talks to a real rcssserver3d or to ours; the in-process transport (later, for training) hands the
same bytes to a ``sim`` session directly.
"""

from __future__ import annotations

import socket
from typing import Protocol

from world.framing import FrameDecoder, frame


class ServerGoneError(ConnectionError):
    """The server closed the connection or cannot be reached; the message says which."""


class Transport(Protocol):
    def send(self, payload: bytes) -> None: ...

    def receive(self) -> bytes: ...

    def close(self) -> None: ...


class TcpTransport:
    """Length-prefixed messages over one TCP connection (blocking)."""

    def __init__(self, host: str = "127.0.0.1", port: int = 3100, timeout: float = 30.0) -> None:
        try:
            self._sock = socket.create_connection((host, port), timeout=timeout)
        except OSError as exc:
            raise ServerGoneError(f"cannot connect to a server at {host}:{port}: {exc}") from None
        self._sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self._decoder = FrameDecoder()
        self._ready: list[bytes] = []
        self.address = f"{host}:{port}"

    def send(self, payload: bytes) -> None:
        try:
            self._sock.sendall(frame(payload))
        except OSError as exc:
            raise ServerGoneError(f"server {self.address} went away: {exc}") from None

    def receive(self) -> bytes:
        """The next complete message (blocks)."""
        while not self._ready:
            try:
                data = self._sock.recv(65536)
            except TimeoutError:
                raise ServerGoneError(f"server {self.address} sent nothing for too long") from None
            except OSError as exc:
                raise ServerGoneError(f"server {self.address} went away: {exc}") from None
            if not data:
                raise ServerGoneError(f"server {self.address} closed the connection")
            self._ready.extend(self._decoder.feed(data))
        return self._ready.pop(0)

    def close(self) -> None:
        self._sock.close()
