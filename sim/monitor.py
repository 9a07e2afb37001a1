"""Trainer commands: what monitors and trainer tools send to the server on port 3200.

:func:`parse_trainer_commands` turns one monitor message into typed commands plus one error per
bad command (the good ones are kept). The command set is that of rcssserver3d 0.7.2's
``TrainerCommandParser`` (``trainercommandparser.cpp``); each command acts on the next cycle.

==========================================  ==============================  ====================
wire form                                   command                         real server effect
==========================================  ==============================  ====================
``(playMode MODE)``                         :class:`SetPlayMode`            set the play mode
``(ball (pos x y z) (vel x y z))``          :class:`MoveBall`               place / push ball;
                                                                            either part optional
``(agent (unum N) (team Left|Right)``       :class:`MoveAgent`              ``pos``: move all
``  [(pos x y z)] [(move x y z deg)]``                                      bodies; ``move``:
``  [(rot x y z)] [(battery B)]``                                           also turn upright to
``  [(temperature T)])``                                                    ``deg`` (0 faces +y)
``(agent)`` (no unum, no team)              :class:`ResetSelection`         clear the selection
``(kickOff Left|Right|None)``               :class:`KickOff`                kick off
``(dropBall)``                              :class:`DropBall`               drop ball
``(select (unum N) (team T))``              :class:`SelectAgent`            select that player
``(select (unum -1))``                      :class:`ResetSelection`         clear the selection
``(select)``                                :class:`SelectNextAgent`        select the next one
``(kill (unum N) (team T))`` / ``(kill)``   :class:`KillAgent` /            remove the player /
                                            :class:`KillSelectedAgent`      the selected one
``(repos (unum N) (team T))`` / ``(repos)`` :class:`ReposAgent` /           move the player out
                                            :class:`ReposSelectedAgent`     of the ball's way
``(reqfullstate)``                          :class:`RequestFullState`       next message is full
``(time T)``                                :class:`SetTime`                set game time (>= 0)
``(score (left L) (right R))``              :class:`SetScore`               set the score
``(getAck)``                                :class:`RequestAck`             reply ``best`` once
``(killsim)``                               :class:`KillSimulation`         stop the server
==========================================  ==============================  ====================

Parsed but without effect in a simulation without batteries and motor heat: ``battery`` and
``temperature`` of ``agent`` (kept on :class:`MoveAgent` for completeness, no error). Which
commands the stand-in server applies is up to ``sim.session``; it must log the others as not
implemented rather than drop them silently.

This parser is stricter than the real one where the real one silently does nothing: unknown
command names, unknown parts (``(ball (poss ...))``), wrong counts of numbers, non-finite
numbers, unknown play modes or team names and negative times or scores are errors. Team names
are case-sensitive (``Left``, ``Right``), as on the real server.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from world.play_modes import PLAY_MODES
from world.sexp import SExpr, SExpressionError, atom_number, dumps, parse

Team = Literal["Left", "Right"]
KickOffSide = Literal["Left", "Right", "None"]
Vec3 = tuple[float, float, float]


class TrainerCommandError(ValueError):
    """One trainer command that cannot be understood; the message says why."""


# ----------------------------------------------------------------------------- commands


@dataclass(frozen=True, slots=True)
class TrainerCommand:
    """Base class of every trainer command."""


@dataclass(frozen=True, slots=True)
class SetPlayMode(TrainerCommand):
    """``(playMode MODE)``; ``mode`` is one of :data:`world.play_modes.PLAY_MODES`."""

    mode: str


@dataclass(frozen=True, slots=True)
class MoveBall(TrainerCommand):
    """``(ball (pos x y z) (vel x y z))``. A velocity also stops the ball's spin (real server).
    ``None`` leaves that part as it is."""

    position: Vec3 | None = None
    velocity: Vec3 | None = None


@dataclass(frozen=True, slots=True)
class MoveAgent(TrainerCommand):
    """``(agent (unum N) (team Left|Right) ...)``: place one robot, all bodies together.

    ``position`` is the torso's new position (from ``pos``, or from ``move`` which wins when both
    are given, as the server applies ``move`` after ``pos``). ``rotation_deg`` (from ``move``)
    turns the robot upright to that heading; the angle is raw: 0 faces world +y, unlike
    ``beam``. ``euler_deg`` (from ``rot``) is an extra rotation applied last. Velocities are
    zeroed. ``battery`` and ``temperature`` have no effect in our simulation.
    """

    unum: int
    team: Team
    position: Vec3 | None = None
    rotation_deg: float | None = None
    euler_deg: Vec3 | None = None
    battery: float | None = None
    temperature: float | None = None


@dataclass(frozen=True, slots=True)
class KillAgent(TrainerCommand):
    """``(kill (unum N) (team T))``: disconnect that player's agent."""

    unum: int
    team: Team


@dataclass(frozen=True, slots=True)
class KillSelectedAgent(TrainerCommand):
    """``(kill)``: disconnect the selected player's agent."""


@dataclass(frozen=True, slots=True)
class ReposAgent(TrainerCommand):
    """``(repos (unum N) (team T))``: move that player to a legal spot away from the ball."""

    unum: int
    team: Team


@dataclass(frozen=True, slots=True)
class ReposSelectedAgent(TrainerCommand):
    """``(repos)``: reposition the selected player."""


@dataclass(frozen=True, slots=True)
class SelectAgent(TrainerCommand):
    """``(select (unum N) (team T))``: make that player the selected one."""

    unum: int
    team: Team


@dataclass(frozen=True, slots=True)
class SelectNextAgent(TrainerCommand):
    """``(select)``: select the next player."""


@dataclass(frozen=True, slots=True)
class ResetSelection(TrainerCommand):
    """``(select (unum -1))`` or ``(agent)``: no player selected."""


@dataclass(frozen=True, slots=True)
class KickOff(TrainerCommand):
    """``(kickOff Left|Right|None)``: ``None`` lets the server pick the side."""

    side: KickOffSide


@dataclass(frozen=True, slots=True)
class DropBall(TrainerCommand):
    """``(dropBall)``: a drop ball at the ball's position."""


@dataclass(frozen=True, slots=True)
class RequestFullState(TrainerCommand):
    """``(reqfullstate)``: the next monitor message is a full state."""


@dataclass(frozen=True, slots=True)
class SetTime(TrainerCommand):
    """``(time T)``: set the game time (seconds, >= 0)."""

    time: float


@dataclass(frozen=True, slots=True)
class SetScore(TrainerCommand):
    """``(score (left L) (right R))``: set both scores (>= 0)."""

    left: int
    right: int


@dataclass(frozen=True, slots=True)
class RequestAck(TrainerCommand):
    """``(getAck)``: the real server answers ``best`` with its next monitor message."""


@dataclass(frozen=True, slots=True)
class KillSimulation(TrainerCommand):
    """``(killsim)``: shut the server down."""


# ----------------------------------------------------------------------------- parsing


def parse_trainer_commands(payload: bytes | str) -> tuple[list[TrainerCommand], list[str]]:
    """Parse one monitor message into commands and errors (one per bad command).

    A message that is not well-formed S-expressions gives no commands and one error.
    """
    try:
        expressions = parse(payload)
    except SExpressionError as exc:
        return [], [f"unreadable trainer message: {exc}"]
    commands: list[TrainerCommand] = []
    errors: list[str] = []
    for expr in expressions:
        try:
            commands.append(parse_trainer_command(expr))
        except TrainerCommandError as exc:
            errors.append(f"{_excerpt(expr)}: {exc}")
    return commands, errors


def parse_trainer_command(expr: SExpr) -> TrainerCommand:
    """One command from its parsed expression; :class:`TrainerCommandError` says what is
    wrong."""
    if not isinstance(expr, list) or not expr or not isinstance(expr[0], str):
        raise TrainerCommandError("a command is a list that starts with its name")
    name, args = expr[0], expr[1:]
    parser = _PARSERS.get(name)
    if parser is None:
        raise TrainerCommandError(
            f"unknown trainer command {name!r}; known: {', '.join(sorted(_PARSERS))}"
        )
    return parser(args)


def _excerpt(expr: SExpr, limit: int = 80) -> str:
    try:
        text = dumps(expr)
    except SExpressionError:
        text = repr(expr)
    return text if len(text) <= limit else text[: limit - 3] + "..."


# -- values ---------------------------------------------------------------------------------


def _number(atom: SExpr, what: str) -> float:
    try:
        return atom_number(atom)
    except ValueError as exc:
        raise TrainerCommandError(f"{what}: {exc}") from None


def _integer(atom: SExpr, what: str) -> int:
    value = _number(atom, what)
    if not value.is_integer():
        raise TrainerCommandError(f"{what}: {atom!r} is not an integer")
    return int(value)


def _numbers(values: list[SExpr], count: int, what: str) -> tuple[float, ...]:
    if len(values) != count:
        raise TrainerCommandError(f"{what}: expected {count} numbers, got {len(values)}")
    return tuple(_number(v, what) for v in values)


def _vec3(values: list[SExpr], what: str) -> Vec3:
    x, y, z = _numbers(values, 3, what)
    return (x, y, z)


def _parts(args: list[SExpr], allowed: tuple[str, ...], command: str) -> dict[str, list[SExpr]]:
    """``(key value...)`` sub-lists by key; unknown, repeated or malformed parts are errors."""
    parts: dict[str, list[SExpr]] = {}
    for arg in args:
        if not isinstance(arg, list) or not arg or not isinstance(arg[0], str):
            raise TrainerCommandError(f"{command}: expected parts like (key value), got {arg!r}")
        key = arg[0]
        if key not in allowed:
            raise TrainerCommandError(
                f"{command}: unknown part {key!r}; allowed: {', '.join(allowed)}"
            )
        if key in parts:
            raise TrainerCommandError(f"{command}: part {key!r} given twice")
        parts[key] = arg[1:]
    return parts


def _single_atom(args: list[SExpr], command: str, meaning: str) -> str:
    if len(args) != 1 or not isinstance(args[0], str):
        raise TrainerCommandError(f"{command}: expected one {meaning}")
    return args[0]


def _no_args(args: list[SExpr], command: str) -> None:
    if args:
        raise TrainerCommandError(f"{command} takes no arguments")


def _team(values: list[SExpr], command: str) -> Team:
    team = _single_atom(values, command, "team (Left or Right)")
    if team == "Left":
        return "Left"
    if team == "Right":
        return "Right"
    raise TrainerCommandError(f"{command}: team must be Left or Right, got {team!r}")


def _player(parts: dict[str, list[SExpr]], command: str) -> tuple[int, Team] | None:
    """``(unum N) (team T)``, or None when both are missing (the selected player)."""
    if "unum" not in parts and "team" not in parts:
        return None
    if "unum" not in parts or "team" not in parts:
        raise TrainerCommandError(f"{command}: give both (unum N) and (team Left|Right)")
    if len(parts["unum"]) != 1:
        raise TrainerCommandError(f"{command}: expected (unum N)")
    return _integer(parts["unum"][0], f"{command} unum"), _team(parts["team"], command)


# -- commands -------------------------------------------------------------------------------


def _parse_play_mode(args: list[SExpr]) -> TrainerCommand:
    mode = _single_atom(args, "playMode", "play mode name")
    if mode not in PLAY_MODES:
        raise TrainerCommandError(f"unknown play mode {mode!r}; valid: {', '.join(PLAY_MODES)}")
    return SetPlayMode(mode)


def _parse_ball(args: list[SExpr]) -> TrainerCommand:
    parts = _parts(args, ("pos", "vel"), "ball")
    if not parts:
        raise TrainerCommandError("ball: give (pos x y z) and/or (vel x y z)")
    position = _vec3(parts["pos"], "ball pos") if "pos" in parts else None
    velocity = _vec3(parts["vel"], "ball vel") if "vel" in parts else None
    return MoveBall(position, velocity)


_AGENT_PARTS = ("unum", "team", "pos", "move", "rot", "battery", "temperature")


def _parse_agent(args: list[SExpr]) -> TrainerCommand:
    parts = _parts(args, _AGENT_PARTS, "agent")
    player = _player(parts, "agent")
    if player is None:
        if parts:
            raise TrainerCommandError("agent: give (unum N) (team Left|Right) to move a player")
        return ResetSelection()
    unum, team = player
    position = _vec3(parts["pos"], "agent pos") if "pos" in parts else None
    rotation = None
    if "move" in parts:
        x, y, z, rotation = _numbers(parts["move"], 4, "agent move (x y z deg)")
        position = (x, y, z)
    euler = _vec3(parts["rot"], "agent rot") if "rot" in parts else None
    battery = _numbers(parts["battery"], 1, "agent battery")[0] if "battery" in parts else None
    temperature = (
        _numbers(parts["temperature"], 1, "agent temperature")[0]
        if "temperature" in parts
        else None
    )
    return MoveAgent(unum, team, position, rotation, euler, battery, temperature)


def _player_command(
    name: str,
    specific: Callable[[int, Team], TrainerCommand],
    selected: Callable[[], TrainerCommand],
) -> Callable[[list[SExpr]], TrainerCommand]:
    """``kill``/``repos``: a given player, or the selected one when none is named."""

    def parse_command(args: list[SExpr]) -> TrainerCommand:
        player = _player(_parts(args, ("unum", "team"), name), name)
        return selected() if player is None else specific(*player)

    return parse_command


def _parse_select(args: list[SExpr]) -> TrainerCommand:
    parts = _parts(args, ("unum", "team"), "select")
    unum = parts.get("unum", [])
    if len(unum) == 1 and _integer(unum[0], "select unum") == -1:  # with or without a team
        return ResetSelection()
    player = _player(parts, "select")
    return SelectNextAgent() if player is None else SelectAgent(*player)


def _parse_kick_off(args: list[SExpr]) -> TrainerCommand:
    side = _single_atom(args, "kickOff", "side (Left, Right or None)")
    if side not in ("Left", "Right", "None"):
        raise TrainerCommandError(f"kickOff: side must be Left, Right or None, got {side!r}")
    return KickOff(side)  # type: ignore[arg-type]  # checked just above


def _parse_time(args: list[SExpr]) -> TrainerCommand:
    time = _numbers(args, 1, "time")[0]
    if time < 0:
        raise TrainerCommandError(f"time: {time:g} cannot be negative")
    return SetTime(time)


def _parse_score(args: list[SExpr]) -> TrainerCommand:
    parts = _parts(args, ("left", "right"), "score")
    scores = []
    for side in ("left", "right"):
        if side not in parts or len(parts[side]) != 1:
            raise TrainerCommandError("score: expected (score (left L) (right R))")
        score = _integer(parts[side][0], f"score {side}")
        if score < 0:
            raise TrainerCommandError(f"score {side}: {score} cannot be negative")
        scores.append(score)
    return SetScore(*scores)


def _no_arg_command(
    name: str, command: Callable[[], TrainerCommand]
) -> Callable[[list[SExpr]], TrainerCommand]:
    def parse_command(args: list[SExpr]) -> TrainerCommand:
        _no_args(args, name)
        return command()

    return parse_command


_PARSERS: dict[str, Callable[[list[SExpr]], TrainerCommand]] = {
    "agent": _parse_agent,
    "ball": _parse_ball,
    "playMode": _parse_play_mode,
    "dropBall": _no_arg_command("dropBall", DropBall),
    "kickOff": _parse_kick_off,
    "getAck": _no_arg_command("getAck", RequestAck),
    "select": _parse_select,
    "kill": _player_command("kill", KillAgent, KillSelectedAgent),
    "repos": _player_command("repos", ReposAgent, ReposSelectedAgent),
    "killsim": _no_arg_command("killsim", KillSimulation),
    "reqfullstate": _no_arg_command("reqfullstate", RequestFullState),
    "time": _parse_time,
    "score": _parse_score,
}
