"""The client -> server direction of the agent protocol: effector messages.

An agent answers every perception with one message holding any of ``(scene PATH TYPE)``,
``(init (unum N)(teamname NAME))``, ``(beam X Y DEG)``, joint speeds such as ``(he1 0.5)``,
``(say MSG)`` and ``(syn)``. The real server ignores items it cannot use and keeps the rest, so
:func:`parse_effectors` does the same and reports each bad item as a readable error text.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from world.sexp import SExpr, SExpressionError, atom_number, dumps, parse

#: every joint effector name, head, arms (right, left) then legs (right, left); the 7th leg
#: joint (toe) exists only on robot type 4, which the server checks, not the codec
JOINT_EFFECTORS: tuple[str, ...] = (
    "he1",
    "he2",
    *(f"rae{i}" for i in range(1, 5)),
    *(f"lae{i}" for i in range(1, 5)),
    *(f"rle{i}" for i in range(1, 8)),
    *(f"lle{i}" for i in range(1, 8)),
)
_JOINT_EFFECTOR_SET = frozenset(JOINT_EFFECTORS)

#: effector prefix <-> perceptor prefix of the same joints
_PERCEPTOR_OF_EFFECTOR_PREFIX = {"he": "hj", "rae": "raj", "lae": "laj", "rle": "rlj", "lle": "llj"}
_EFFECTOR_OF_PERCEPTOR_PREFIX = {v: k for k, v in _PERCEPTOR_OF_EFFECTOR_PREFIX.items()}


@dataclass(slots=True)
class EffectorMessage:
    """Everything one client message asks for. Unset items are ``None``/empty."""

    #: (rsg path, robot type 0..4): creates the robot; sent once, first
    scene: tuple[str, int] | None = None
    #: (uniform number, team name); unum 0 lets the server choose
    init: tuple[int, str] | None = None
    #: (x, y, degrees): place the robot on its own half before kick-off
    beam: tuple[float, float, float] | None = None
    #: joint effector name (``he1`` ... ``lle7``) -> target speed in rad/s, in message order
    joint_speeds: dict[str, float] = field(default_factory=dict)
    #: a message for the other robots to hear
    say: str | None = None
    #: the sync-mode "done with this cycle" marker
    syn: bool = False


def effector_for_joint(perceptor: str) -> str:
    """The effector that drives the joint a perceptor reports: ``"rlj3" -> "rle3"``."""
    return _rename(perceptor, _EFFECTOR_OF_PERCEPTOR_PREFIX, "joint perceptor")


def joint_for_effector(effector: str) -> str:
    """The perceptor that reports the joint an effector drives: ``"rle3" -> "rlj3"``."""
    return _rename(effector, _PERCEPTOR_OF_EFFECTOR_PREFIX, "joint effector")


def _rename(name: str, prefixes: dict[str, str], what: str) -> str:
    prefix, number = name.rstrip("0123456789"), name[len(name.rstrip("0123456789")) :]
    if prefix not in prefixes or not number:
        raise ValueError(
            f"{name!r} is not a {what} name (expected one of {sorted(prefixes)} and a number)"
        )
    return prefixes[prefix] + number


def _integer(atom: SExpr) -> int:
    if not isinstance(atom, str):
        raise ValueError(f"expected an integer, got {dumps(atom)}")
    try:
        return int(atom)
    except ValueError:
        raise ValueError(f"expected an integer, got {atom!r}") from None


def _name(atom: SExpr) -> str:
    if not isinstance(atom, str):
        raise ValueError(f"expected a name, got {dumps(atom)}")
    return atom


def _arity(expr: list[SExpr], *counts: int) -> list[SExpr]:
    args = expr[1:]
    if len(args) not in counts:
        wanted = " or ".join(str(c) for c in counts)
        raise ValueError(f"takes {wanted} value(s), got {len(args)}")
    return args


def _read_scene(msg: EffectorMessage, expr: list[SExpr]) -> None:
    args = _arity(expr, 1, 2)
    robot_type = _integer(args[1]) if len(args) == 2 else 0
    msg.scene = (_name(args[0]), robot_type)


def _read_init(msg: EffectorMessage, expr: list[SExpr]) -> None:
    unum, team = 0, None
    for item in expr[1:]:
        if not isinstance(item, list) or len(item) != 2:
            raise ValueError(f"expected (unum N) or (teamname NAME), got {dumps(item)}")
        key, value = item
        if key == "unum":
            unum = _integer(value)
        elif key == "teamname":
            team = _name(value)
        else:
            raise ValueError(f"unknown init parameter {dumps(item)}")
    if team is None:
        raise ValueError("needs (teamname NAME)")
    msg.init = (unum, team)


def _read_beam(msg: EffectorMessage, expr: list[SExpr]) -> None:
    x, y, angle = _arity(expr, 3)
    msg.beam = (atom_number(x), atom_number(y), atom_number(angle))


def _read_say(msg: EffectorMessage, expr: list[SExpr]) -> None:
    (text,) = _arity(expr, 1)
    msg.say = _name(text)


def _read_syn(msg: EffectorMessage, expr: list[SExpr]) -> None:
    _arity(expr, 0)
    msg.syn = True


_READERS = {
    "scene": _read_scene,
    "init": _read_init,
    "beam": _read_beam,
    "say": _read_say,
    "syn": _read_syn,
}


# The fast path: what agents send nearly every cycle, joint speeds then optionally a say and the
# syn, in write_effectors' layout. A message that matches _CANONICAL_MESSAGE as a whole holds
# nothing else, and atoms hold no parentheses, so the findall patterns cannot pick up a piece
# from the wrong place. Anything else, or a number that does not read, takes the general path.
_ATOM = r"[^\s()]+"
_JOINT_NAME = r"(?:he[12]|[rl]ae[1-4]|[rl]le[1-7])"
_CANONICAL_MESSAGE = re.compile(rf"(?:\({_JOINT_NAME} {_ATOM}\))*(?:\(say {_ATOM}\))?(?:\(syn\))?")
_JOINT_SPEED = re.compile(rf"\(({_JOINT_NAME}) ({_ATOM})\)")
_SAY = re.compile(rf"\(say ({_ATOM})\)")


def parse_effectors(payload: bytes | str) -> tuple[EffectorMessage, list[str]]:
    """Read one client message; return what it asks for and one error text per bad item.

    Bad items (unknown effector, wrong number of values, a word where a number belongs) are
    left out and reported, the good ones kept, as the real server does. A message that is not
    well-formed S-expressions yields an empty :class:`EffectorMessage` and one error.
    """
    fast = _parse_canonical(payload)
    if fast is not None:
        return fast, []
    return _parse_general(payload)


def _parse_canonical(payload: bytes | str) -> EffectorMessage | None:
    """The message, if it has the common layout and every number reads; None otherwise."""
    try:
        text = payload.decode("ascii") if isinstance(payload, bytes) else payload
    except UnicodeDecodeError:
        return None
    if _CANONICAL_MESSAGE.fullmatch(text) is None:
        return None
    msg = EffectorMessage()
    try:
        for name, speed in _JOINT_SPEED.findall(text):
            msg.joint_speeds[name] = atom_number(speed)
    except ValueError:
        return None
    said = _SAY.search(text)
    if said is not None:
        msg.say = said.group(1)
    msg.syn = text.endswith("(syn)")
    return msg


def _parse_general(payload: bytes | str) -> tuple[EffectorMessage, list[str]]:
    """Tolerant path: any layout and spacing, precise errors."""
    msg = EffectorMessage()
    errors: list[str] = []
    try:
        exprs = parse(payload)
    except SExpressionError as exc:
        return msg, [f"message ignored: {exc}"]
    for expr in exprs:
        head = expr[0] if isinstance(expr, list) and expr else None
        if not isinstance(head, str):
            errors.append(f"item without an effector name: {dumps(expr)}")
            continue
        try:
            if head in _JOINT_EFFECTOR_SET:
                (speed,) = _arity(expr, 1)
                msg.joint_speeds[head] = atom_number(speed)
            elif head in _READERS:
                _READERS[head](msg, expr)
            else:
                errors.append(f"unknown effector {head!r} in {dumps(expr)}")
        except ValueError as exc:
            errors.append(f"bad {head} effector {dumps(expr)}: {exc}")
    return msg, errors


def _short(value: float) -> str:
    """Shortest text that reads back as the same float (``0.5``, ``-1.0``)."""
    number = float(value)
    if not math.isfinite(number):
        raise SExpressionError(f"cannot send the non-finite number {value!r}")
    return repr(number)


def _check_names(msg: EffectorMessage) -> None:
    names = list(msg.joint_speeds)
    if msg.scene is not None:
        names.append(msg.scene[0])
    if msg.init is not None:
        names.append(msg.init[1])
    if msg.say is not None:
        names.append(msg.say)
    for name in names:
        dumps(name)  # raises SExpressionError for anything that is not a single atom


def write_effectors(msg: EffectorMessage) -> bytes:
    """Write ``msg`` as a client sends it, e.g. ``(he1 0.5)(lle4 -1.0)(syn)``.

    Order: scene, init, beam, joint speeds (in ``joint_speeds`` order), say, syn. Raises
    :class:`~world.sexp.SExpressionError` for a name that would change what the server reads
    (empty, or with a space or parenthesis) and for non-finite numbers.
    """
    _check_names(msg)
    out = []
    if msg.scene is not None:
        path, robot_type = msg.scene
        out.append(f"(scene {path} {int(robot_type)})")
    if msg.init is not None:
        unum, team = msg.init
        out.append(f"(init (unum {int(unum)})(teamname {team}))")
    if msg.beam is not None:
        out.append("(beam " + " ".join(_short(v) for v in msg.beam) + ")")
    out.extend(f"({name} {_short(speed)})" for name, speed in msg.joint_speeds.items())
    if msg.say is not None:
        out.append(f"(say {msg.say})")
    if msg.syn:
        out.append("(syn)")
    return "".join(out).encode("ascii")
