"""S-expression reader and writer for the SimSpark wire protocol.

Every message on both server ports is a sequence of parenthesised S-expressions such as
``(time (now 5.22))(GS (sl 0) (sr 0))``. Atoms are runs of characters other than whitespace
and parentheses; they stay strings here (numbers are converted by whoever knows what an atom
means, see :mod:`world.perception` and :mod:`world.effectors`).

The reader is tuned for CPython: one regular expression ``findall`` splits the text into
tokens, where a whole innermost list such as ``(pol 3.02 1.07 -9.53)`` is one token split by
``str.split`` in C. A perception message then needs a Python-level loop over about 260 tokens
instead of about 660.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from typing import TypeAlias

#: An atom (a string) or a list of S-expressions.
SExpr: TypeAlias = str | list["SExpr"]

#: innermost list | single parenthesis | atom
_TOKEN = re.compile(r"\([^()]*\)|[()]|[^\s()]+")
#: characters an atom may not contain: they would change the structure when written
_NOT_ATOM = re.compile(r"[\s()]")


class ProtocolError(ValueError):
    """A message that does not follow the wire protocol."""


class SExpressionError(ProtocolError):
    """Text that is not a well-formed sequence of S-expressions, or a value that cannot be
    written as one."""


def _decode(text: str | bytes | bytearray | memoryview) -> str:
    """Return ``text`` as ``str``; the protocol is ASCII, so UTF-8 decoding is a superset."""
    if isinstance(text, str):
        return text
    try:
        return bytes(text).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SExpressionError(f"message is not ASCII/UTF-8 text: {exc}") from None


def _excerpt(text: str, limit: int = 60) -> str:
    """A short, printable piece of ``text`` for error messages."""
    return repr(text if len(text) <= limit else text[:limit] + "...")


def parse(text: str | bytes) -> list[SExpr]:
    """Parse a message into its top-level expressions.

    ``parse("(a (b 1))(c)") == [["a", ["b", "1"]], ["c"]]``. Raises :class:`SExpressionError`
    on unbalanced parentheses, on text outside any parentheses (the protocol has none), and on
    bytes that are not text.
    """
    source = _decode(text)
    stack: list[list[SExpr]] = []
    current: list[SExpr] = []
    for token in _TOKEN.findall(source):
        first = token[0]
        if first == "(":
            if len(token) == 1:
                stack.append(current)
                current = []
            else:
                current.append(token[1:-1].split())
        elif first == ")":
            if not stack:
                raise SExpressionError(
                    f"unbalanced parentheses: unexpected ')' in {_excerpt(source)}"
                )
            parent = stack.pop()
            parent.append(current)
            current = parent
        else:
            current.append(token)
    if stack:
        raise SExpressionError(
            f"unbalanced parentheses: {len(stack)} '(' never closed in {_excerpt(source)}"
        )
    for expr in current:
        if isinstance(expr, str):
            raise SExpressionError(f"garbage outside parentheses: {expr!r} in {_excerpt(source)}")
    return current


def _check_atom(atom: str) -> str:
    if not atom or _NOT_ATOM.search(atom):
        raise SExpressionError(
            f"cannot write atom {atom!r}: atoms must be non-empty and free of whitespace "
            "and parentheses"
        )
    return atom


def dumps(expr: SExpr) -> str:
    """Write one expression: lists as ``(a b c)`` with single spaces, atoms as they are.

    Raises :class:`SExpressionError` for an atom that could not be read back as the same atom
    (empty, or containing whitespace or parentheses) and for values that are neither ``str``
    nor ``list``.
    """
    if isinstance(expr, str):
        return _check_atom(expr)
    if isinstance(expr, list):
        return "(" + " ".join([dumps(item) for item in expr]) + ")"
    raise SExpressionError(f"cannot write {type(expr).__name__} {expr!r}: expected str or list")


def dumps_all(exprs: Iterable[SExpr]) -> str:
    """Write a sequence of top-level lists back to back, as messages are sent on the wire.

    Top-level atoms are refused (the reader would refuse them too).
    """
    pieces = []
    for expr in exprs:
        if not isinstance(expr, list):
            raise SExpressionError(f"top-level expressions must be lists, got {expr!r}")
        pieces.append(dumps(expr))
    return "".join(pieces)


def atom_number(atom: SExpr) -> float:
    """The finite float an atom spells; ValueError saying why not (a list, not a number,
    NaN or infinity). Shared by every parser of numbers in messages (effectors, trainer)."""
    if not isinstance(atom, str):
        raise ValueError(f"expected a number, got {dumps(atom)}")
    try:
        value = float(atom)
    except ValueError:
        raise ValueError(f"{atom!r} is not a number") from None
    if not math.isfinite(value):
        raise ValueError(f"{atom!r} is not a finite number")
    return value
