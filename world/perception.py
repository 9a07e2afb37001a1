"""Typed perceptions: what one server message tells an agent.

The classes here are the contract between the codec (parsing and writing the wire format), the
server's perceptor generation and the agent's world model. Angles are degrees, distances metres,
as on the wire.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from world.field_geometry import LANDMARKS
from world.sexp import ProtocolError, SExpr, dumps, parse

#: The server's cycle: one perception and one physics step every 0.02 s (rcssserver3d's
#: ``simulationtime``). The single definition; robot state, joint control and the simulator
#: import it from here.
CYCLE_SECONDS = 0.02

__all__ = [
    "FRP_BEFORE_JOINT",
    "ForceResistance",
    "GameState",
    "Heard",
    "Perception",
    "Polar",
    "ProtocolError",
    "SeenPlayer",
    "Vision",
    "parse_perception",
    "write_perception",
]


@dataclass(slots=True)
class Polar:
    """A vision measurement relative to the camera: distance (m), horizontal angle phi (deg,
    positive to the left) and vertical angle theta (deg, positive up)."""

    distance: float
    phi: float
    theta: float


@dataclass(slots=True)
class SeenPlayer:
    """Another robot (or the robot's own lower arms) as vision reports it."""

    team: str
    unum: int
    #: body part name (``head``, ``rlowerarm``, ``llowerarm``, ``rfoot``, ``lfoot``) -> polar,
    #: in the order the server wrote them.
    parts: dict[str, Polar] = field(default_factory=dict)


@dataclass(slots=True)
class Vision:
    """One ``See`` perceptor reading."""

    #: flags and goal posts (F1L ... G2R) -> polar, in message order
    landmarks: dict[str, Polar] = field(default_factory=dict)
    ball: Polar | None = None
    players: list[SeenPlayer] = field(default_factory=list)
    #: field line segments clipped to the view cone, as pairs of end points
    lines: list[tuple[Polar, Polar]] = field(default_factory=list)
    #: how many of ``players`` the server wrote before the landmarks and the ball. The real
    #: server groups seen objects by scene node (one group for the field objects, one per
    #: robot) and writes the groups in memory-address order, so this varies between runs; it
    #: only matters for writing messages byte for byte. 0 (the default) writes landmarks and
    #: ball first; the reader sets 0 whenever no landmark or ball is seen.
    players_before_landmarks: int = 0


@dataclass(slots=True)
class GameState:
    """The ``GS`` perceptor. ``unum`` and ``team`` ('left'/'right') appear in one message only."""

    game_time: float = 0.0
    play_mode: str = "BeforeKickOff"
    score_left: int = 0
    score_right: int = 0
    unum: int | None = None
    team: str | None = None


@dataclass(slots=True)
class ForceResistance:
    """A foot (``lf``, ``rf``) or toe (``lf1``, ``rf1``) pressure reading: contact point (m) and
    force (N) in the foot's frame. Present only while the foot touches something."""

    name: str
    contact: tuple[float, float, float]
    force: tuple[float, float, float]


@dataclass(slots=True)
class Heard:
    """A ``hear`` message: ``direction`` is ``'self'`` or a horizontal angle in degrees."""

    team: str
    time: float
    direction: str | float
    message: str


@dataclass(slots=True)
class Perception:
    """Everything in one perception message from the server."""

    time: float = 0.0
    game_state: GameState = field(default_factory=GameState)
    gyro: tuple[float, float, float] = (0.0, 0.0, 0.0)
    accelerometer: tuple[float, float, float] = (0.0, 0.0, 0.0)
    #: joint perceptor name (hj1, raj1, ..., llj6[, llj7]) -> angle in degrees, in message order
    joints: dict[str, float] = field(default_factory=dict)
    #: foot/toe pressure perceptor name -> reading, only for feet in contact
    force_resistance: dict[str, ForceResistance] = field(default_factory=dict)
    vision: Vision | None = None
    heard: list[Heard] = field(default_factory=list)


# --------------------------------------------------------------------------------------------
# Wire codec: parse_perception / write_perception
#
# The reader works on the nested lists of world.sexp.parse (one regex findall plus a small stack
# walk) and converts each top-level perceptor with a small function picked from a table. The
# writer reproduces the real server's output byte for byte: its order of perceptors, '%.2f' for
# every float (so '-0.00' survives as -0.0) and single spaces inside a perceptor.
# --------------------------------------------------------------------------------------------

#: foot/toe pressure perceptor -> the joint whose HJ the server writes right after it
FRP_BEFORE_JOINT: dict[str, str] = {"rf": "rlj6", "rf1": "rlj7", "lf": "llj6", "lf1": "llj7"}
#: joints the server writes before the See perceptor (the head), all others come after it
_HEAD_JOINTS = ("hj1", "hj2")
_LANDMARK_NAMES = frozenset(LANDMARKS)


def _f2(value: float) -> str:
    """The server's number format for floats: two decimals, sign of zero kept."""
    return "%.2f" % value  # noqa: UP031 (measurably faster than format() on the hot path)


def _float(atom: SExpr) -> float:
    if not isinstance(atom, str):
        raise ProtocolError(f"expected a number, got the list {dumps(atom)}")
    try:
        return float(atom)
    except ValueError:
        raise ProtocolError(f"expected a number, got {atom!r}") from None


def _int(atom: SExpr) -> int:
    if not isinstance(atom, str):
        raise ProtocolError(f"expected an integer, got the list {dumps(atom)}")
    try:
        return int(atom)
    except ValueError:
        raise ProtocolError(f"expected an integer, got {atom!r}") from None


def _atom(item: SExpr) -> str:
    if not isinstance(item, str):
        raise ProtocolError(f"expected a name, got the list {dumps(item)}")
    return item


def _leaf(item: SExpr, key: str, arity: int) -> list[SExpr]:
    """Check that ``item`` is ``(key v1 .. v_arity)`` and return the values."""
    if not isinstance(item, list) or len(item) != arity + 1 or item[0] != key:
        shown = dumps(item) if isinstance(item, (str, list)) else repr(item)
        raise ProtocolError(f"expected ({key} with {arity} value(s)), got {shown}")
    return item[1:]


def _vector(item: SExpr, key: str) -> tuple[float, float, float]:
    x, y, z = _leaf(item, key, 3)
    return (_float(x), _float(y), _float(z))


def _polar(item: SExpr) -> Polar:
    # fast path for the common, well-formed case; _leaf explains anything else
    if type(item) is list and len(item) == 4 and item[0] == "pol":
        try:
            return Polar(float(item[1]), float(item[2]), float(item[3]))
        except (TypeError, ValueError):
            pass
    distance, phi, theta = _leaf(item, "pol", 3)
    return Polar(_float(distance), _float(phi), _float(theta))


def _read_time(p: Perception, expr: list[SExpr]) -> None:
    (now,) = _leaf(expr, "time", 1)
    p.time = _float(_leaf(now, "now", 1)[0])


def _read_game_state(p: Perception, expr: list[SExpr]) -> None:
    gs = p.game_state
    for item in expr[1:]:
        key = item[0] if isinstance(item, list) and item else None
        if key == "unum":
            gs.unum = _int(_leaf(item, "unum", 1)[0])
        elif key == "team":
            gs.team = _atom(_leaf(item, "team", 1)[0])
        elif key == "sl":
            gs.score_left = _int(_leaf(item, "sl", 1)[0])
        elif key == "sr":
            gs.score_right = _int(_leaf(item, "sr", 1)[0])
        elif key == "t":
            gs.game_time = _float(_leaf(item, "t", 1)[0])
        elif key == "pm":
            gs.play_mode = _atom(_leaf(item, "pm", 1)[0])
        elif key is None:
            raise ProtocolError(f"expected (key value) inside GS, got {dumps(item)}")
        # other keys: a newer server's addition, ignored like unknown perceptors


def _read_hear(p: Perception, expr: list[SExpr]) -> None:
    # 0.7.x: (hear TEAM TIME DIR MSG); before 0.7 there was no TEAM
    args = expr[1:]
    if len(args) == 4:
        team, time, direction, message = args
    elif len(args) == 3:
        team, (time, direction, message) = "", args
    else:
        raise ProtocolError(f"expected (hear TEAM TIME self|DIRECTION MESSAGE), got {dumps(expr)}")
    direction = _atom(direction)
    p.heard.append(
        Heard(
            team=_atom(team),
            time=_float(time),
            direction=direction if direction == "self" else _float(direction),
            message=_atom(message),
        )
    )


def _read_gyro(p: Perception, expr: list[SExpr]) -> None:
    _, _name, rate = expr
    p.gyro = _vector(rate, "rt")


def _read_accelerometer(p: Perception, expr: list[SExpr]) -> None:
    _, _name, acc = expr
    p.accelerometer = _vector(acc, "a")


def _read_hinge_joint(p: Perception, expr: list[SExpr]) -> None:
    # fast path: (HJ (n NAME) (ax DEG)) exactly as every server writes it
    if len(expr) == 3:
        name, axis = expr[1], expr[2]
        if (
            type(name) is list
            and type(axis) is list
            and len(name) == 2
            and len(axis) == 2
            and name[0] == "n"
            and axis[0] == "ax"
            and type(name[1]) is str
        ):
            try:
                p.joints[name[1]] = float(axis[1])
                return
            except (TypeError, ValueError):
                pass
    if len(expr) != 3:
        raise ProtocolError(f"expected (HJ (n NAME) (ax DEG)), got {dumps(expr)}")
    name = _atom(_leaf(expr[1], "n", 1)[0])
    p.joints[name] = _float(_leaf(expr[2], "ax", 1)[0])


def _read_force_resistance(p: Perception, expr: list[SExpr]) -> None:
    if len(expr) != 4:
        raise ProtocolError(f"expected (FRP (n NAME) (c X Y Z) (f X Y Z)), got {dumps(expr)}")
    name = _atom(_leaf(expr[1], "n", 1)[0])
    p.force_resistance[name] = ForceResistance(
        name=name, contact=_vector(expr[2], "c"), force=_vector(expr[3], "f")
    )


def _read_player(item: list[SExpr]) -> SeenPlayer:
    team = ""
    unum = 0
    parts: dict[str, Polar] = {}
    for sub in item[1:]:
        if not isinstance(sub, list) or not sub:
            raise ProtocolError(f"expected (team ..), (id ..) or (PART (pol ..)), got {sub!r}")
        key = sub[0]
        if key == "team":
            team = _atom(_leaf(sub, "team", 1)[0])
        elif key == "id":
            unum = _int(_leaf(sub, "id", 1)[0])
        elif len(sub) == 2 and isinstance(key, str):
            parts[key] = _polar(sub[1])
        else:
            raise ProtocolError(f"expected (PART (pol D PHI THETA)) in P, got {dumps(sub)}")
    return SeenPlayer(team=team, unum=unum, parts=parts)


def _read_vision(p: Perception, expr: list[SExpr]) -> None:
    vision = Vision()
    landmarks = vision.landmarks
    players = vision.players
    players_before_landmarks = -1  # not known until a landmark or the ball shows up
    for item in expr[1:]:
        if type(item) is not list or not item:
            raise ProtocolError(f"expected (OBJECT ...) inside See, got {item!r}")
        key = item[0]
        if key == "L":
            if len(item) != 3:
                raise ProtocolError(f"expected (L (pol ..) (pol ..)), got {dumps(item)}")
            vision.lines.append((_polar(item[1]), _polar(item[2])))
        elif key == "P":
            players.append(_read_player(item))
        elif key == "B" or key in _LANDMARK_NAMES:
            if players_before_landmarks < 0:
                players_before_landmarks = len(players)
            if key == "B":
                vision.ball = _polar(_single(item))
            else:
                landmarks[key] = _polar(_single(item))
        # anything else (mypos, ballpos, ... in other server setups): ignored
    vision.players_before_landmarks = max(players_before_landmarks, 0)
    p.vision = vision


def _single(item: list[SExpr]) -> SExpr:
    if len(item) != 2:
        raise ProtocolError(f"expected ({item[0]} (pol D PHI THETA)), got {dumps(item)}")
    return item[1]


_READERS = {
    "HJ": _read_hinge_joint,
    "FRP": _read_force_resistance,
    "See": _read_vision,
    "time": _read_time,
    "GS": _read_game_state,
    "GYR": _read_gyro,
    "ACC": _read_accelerometer,
    "hear": _read_hear,
}


def parse_perception(payload: bytes | str) -> Perception:
    """Read one perception message (the payload of one frame) from the server.

    Unknown top-level perceptors are skipped so that newer servers stay readable. Raises
    :class:`ProtocolError` (a ``ValueError``) naming the offending perceptor when the message
    is malformed: unbalanced parentheses, a missing value, a word where a number belongs.

    Messages written exactly as the real server writes them (checked by one regular
    expression) take a fast path of a few C-level ``findall`` calls; anything else (other
    spacing, unknown perceptors, errors) goes through the general S-expression reader, which
    gives the same result or explains what is wrong.
    """
    if not isinstance(payload, str):
        try:
            payload = bytes(payload).decode("ascii")
        except UnicodeDecodeError:
            return _parse_general(payload)
    if _CANONICAL_MESSAGE.fullmatch(payload) is not None:
        try:
            return _parse_canonical(payload)
        except (ValueError, TypeError):
            pass  # e.g. a word where a number belongs: let the general reader explain it
    return _parse_general(payload)


def _parse_general(payload: bytes | str) -> Perception:
    """Tolerant path: any spacing, unknown perceptors skipped, precise errors."""
    perception = Perception()
    for expr in parse(payload):
        head = expr[0] if expr else None
        reader = _READERS.get(head) if type(head) is str else None
        if reader is None:
            if type(head) is not str:
                raise ProtocolError(f"perceptor without a name: {dumps(expr)[:80]}")
            continue
        try:
            reader(perception, expr)
        except ProtocolError as exc:
            raise ProtocolError(f"malformed {head} perceptor: {exc}") from None
        except (TypeError, ValueError) as exc:
            raise ProtocolError(f"malformed {head} perceptor {dumps(expr)[:80]}: {exc}") from None
    return perception


# The fast path. _CANONICAL_MESSAGE accepts exactly the real server's layout (single spaces
# inside a perceptor, none between perceptors) and only the perceptors known here. Once a
# message matches it, the findall patterns below cannot pick up a piece from the wrong place:
# atoms hold no parentheses, so e.g. "(HJ (n" only starts a joint perceptor.
_A = r"[^\s()]+"  # an atom
_C = r"([^\s()]+)"  # a captured atom
_POL = rf"\(pol {_A} {_A} {_A}\)"
_OBJECT = rf"\({_A} {_POL}\)"
_CANONICAL_MESSAGE = re.compile(
    "(?:"
    + "|".join(
        [
            rf"\(time \(now {_A}\)\)",
            rf"\(GS(?: \({_A} {_A}\))*\)",
            rf"\(hear(?: {_A}){{3,4}}\)",
            rf"\(GYR \(n {_A}\) \(rt {_A} {_A} {_A}\)\)",
            rf"\(ACC \(n {_A}\) \(a {_A} {_A} {_A}\)\)",
            rf"\(HJ \(n {_A}\) \(ax {_A}\)\)",
            rf"\(FRP \(n {_A}\) \(c {_A} {_A} {_A}\) \(f {_A} {_A} {_A}\)\)",
            rf"\(See(?: (?:{_OBJECT}|\(P \(team {_A}\) \(id {_A}\)(?: {_OBJECT})*\)"
            rf"|\(L {_POL} {_POL}\)))*\)",
        ]
    )
    + ")*"
)
_TIME = re.compile(rf"\(time \(now {_C}\)\)")
_GS = re.compile(r"\(GS((?: \([^()]*\))*)\)")
_GS_ITEM = re.compile(rf"\({_C} {_C}\)")
_HEAR = re.compile(r"\(hear ([^()]*)\)")
_GYR = re.compile(rf"\(GYR \(n {_A}\) \(rt {_C} {_C} {_C}\)\)")
_ACC = re.compile(rf"\(ACC \(n {_A}\) \(a {_C} {_C} {_C}\)\)")
_HJ = re.compile(rf"\(HJ \(n {_C}\) \(ax {_C}\)\)")
_FRP = re.compile(rf"\(FRP \(n {_C}\) \(c {_C} {_C} {_C}\) \(f {_C} {_C} {_C}\)\)")
_CPOL = rf"\(pol {_C} {_C} {_C}\)"
_NAMED_POLAR = rf"\({_A} {_POL}\)"
#: inside See: a whole player (team, id, its parts) | a landmark or the ball (lines don't match)
_SEE_OBJECT = re.compile(rf"\(P \(team {_C}\) \(id {_C}\)((?: {_NAMED_POLAR})*)\)|\({_C} {_CPOL}\)")
_PLAYER_PART = re.compile(rf"\({_C} {_CPOL}\)")
_LINE = re.compile(rf"\(L {_CPOL} {_CPOL}\)")


def _parse_canonical(text: str) -> Perception:
    """Fast path for a message that matched ``_CANONICAL_MESSAGE``."""
    perception = Perception()
    for now in _TIME.findall(text):
        perception.time = float(now)
    for items in _GS.findall(text):
        _apply_game_state(perception.game_state, _GS_ITEM.findall(items))
    for args in _HEAR.findall(text):
        _read_hear(perception, ["hear", *args.split(" ")])
    for x, y, z in _GYR.findall(text):
        perception.gyro = (float(x), float(y), float(z))
    for x, y, z in _ACC.findall(text):
        perception.accelerometer = (float(x), float(y), float(z))
    joints = perception.joints
    for name, angle in _HJ.findall(text):
        joints[name] = float(angle)
    pressure = perception.force_resistance
    for name, cx, cy, cz, fx, fy, fz in _FRP.findall(text):
        pressure[name] = ForceResistance(
            name, (float(cx), float(cy), float(cz)), (float(fx), float(fy), float(fz))
        )
    start = text.find("(See")
    if start >= 0:
        if text.find("(See", start + 4) >= 0:
            raise ValueError("several See perceptors: left to the general reader")
        end = text.find(")(", start)
        perception.vision = _canonical_vision(text[start : len(text) if end < 0 else end + 1])
    return perception


def _apply_game_state(gs: GameState, items: list[tuple[str, str]]) -> None:
    for key, value in items:
        if key == "t":
            gs.game_time = float(value)
        elif key == "pm":
            gs.play_mode = value
        elif key == "sl":
            gs.score_left = int(value)
        elif key == "sr":
            gs.score_right = int(value)
        elif key == "unum":
            gs.unum = int(value)
        elif key == "team":
            gs.team = value


def _canonical_vision(see: str) -> Vision:
    vision = Vision()
    landmarks = vision.landmarks
    players = vision.players
    players_before_landmarks = -1
    for team, unum, parts, name, d, p, t in _SEE_OBJECT.findall(see):
        if team:
            polars = {
                part: Polar(float(pd), float(pp), float(pt))
                for part, pd, pp, pt in _PLAYER_PART.findall(parts)
            }
            if "team" in polars or "id" in polars:
                raise ValueError("a player part named team or id: left to the general reader")
            players.append(SeenPlayer(team, int(unum), polars))
            continue
        if name == "B":
            vision.ball = Polar(float(d), float(p), float(t))
        elif name in _LANDMARK_NAMES:
            landmarks[name] = Polar(float(d), float(p), float(t))
        elif name == "L" or name == "P":
            raise ValueError("a malformed line or player: left to the general reader")
        else:
            continue  # an object a newer server adds
        if players_before_landmarks < 0:
            players_before_landmarks = len(players)
    vision.lines = [
        (Polar(float(d1), float(p1), float(t1)), Polar(float(d2), float(p2), float(t2)))
        for d1, p1, t1, d2, p2, t2 in _LINE.findall(see)
    ]
    vision.players_before_landmarks = max(players_before_landmarks, 0)
    return vision


def _write_polar(polar: Polar) -> str:
    # one %-format per item (the same '%.2f' as _f2): the writer runs for every agent each cycle
    return "(pol %.2f %.2f %.2f)" % (polar.distance, polar.phi, polar.theta)  # noqa: UP031


def _write_player(player: SeenPlayer) -> str:
    parts = "".join(
        [
            " (%s (pol %.2f %.2f %.2f))" % (part, p.distance, p.phi, p.theta)  # noqa: UP031
            for part, p in player.parts.items()
        ]
    )
    return f"(P (team {player.team}) (id {player.unum}){parts})"


def _write_vision(vision: Vision) -> str:
    # real server: one group for the field objects and one per robot, then the lines
    split = vision.players_before_landmarks
    items = [_write_player(player) for player in vision.players[:split]]
    items.extend(
        "(%s (pol %.2f %.2f %.2f))" % (name, p.distance, p.phi, p.theta)  # noqa: UP031
        for name, p in vision.landmarks.items()
    )
    if vision.ball is not None:
        items.append(f"(B {_write_polar(vision.ball)})")
    items.extend(_write_player(player) for player in vision.players[split:])
    items.extend(
        "(L (pol %.2f %.2f %.2f) (pol %.2f %.2f %.2f))"  # noqa: UP031
        % (a.distance, a.phi, a.theta, b.distance, b.phi, b.theta)
        for a, b in vision.lines
    )
    return "(See " + " ".join(items) + ")" if items else "(See)"


def _write_force_resistance(frp: ForceResistance) -> str:
    (cx, cy, cz), (fx, fy, fz) = frp.contact, frp.force
    return "(FRP (n %s) (c %.2f %.2f %.2f) (f %.2f %.2f %.2f))" % (  # noqa: UP031
        frp.name,
        cx,
        cy,
        cz,
        fx,
        fy,
        fz,
    )


def _write_game_state(gs: GameState) -> str:
    who = ""
    if gs.unum is not None:
        who += f"(unum {gs.unum}) "
    if gs.team is not None:
        who += f"(team {gs.team}) "
    return (
        f"(GS {who}(sl {gs.score_left}) (sr {gs.score_right}) "
        f"(t {_f2(gs.game_time)}) (pm {gs.play_mode}))"
    )


def _write_hear(heard: Heard) -> str:
    direction = heard.direction if isinstance(heard.direction, str) else _f2(heard.direction)
    team = f"{heard.team} " if heard.team else ""
    return f"(hear {team}{_f2(heard.time)} {direction} {heard.message})"


def write_perception(p: Perception) -> bytes:
    """Write ``p`` exactly as rcssserver3d 0.7.2 would send it (without the length prefix).

    Order: time, GS, hear..., GYR, ACC, the head joints, See, the other joints in ``p.joints``
    order with each FRP just before its foot's last joint (FRPs whose joint is missing go at
    the end). ``write_perception(parse_perception(m)) == m`` for every message the real server
    sent in the recorded traces.
    """
    gx, gy, gz = p.gyro
    ax, ay, az = p.accelerometer
    out = [
        f"(time (now {_f2(p.time)}))",
        _write_game_state(p.game_state),
        *[_write_hear(h) for h in p.heard],
        "(GYR (n torso) (rt %.2f %.2f %.2f))" % (gx, gy, gz),  # noqa: UP031
        "(ACC (n torso) (a %.2f %.2f %.2f))" % (ax, ay, az),  # noqa: UP031
    ]
    joints = p.joints
    for name in _HEAD_JOINTS:
        if name in joints:
            out.append("(HJ (n %s) (ax %.2f))" % (name, joints[name]))  # noqa: UP031
    if p.vision is not None:
        out.append(_write_vision(p.vision))
    # each FRP goes just before its foot's last joint; FRPs without that joint go last
    frp_before: dict[str, ForceResistance] = {}
    leftovers: list[ForceResistance] = []
    for name, frp in p.force_resistance.items():
        joint = FRP_BEFORE_JOINT.get(name)
        if joint in joints and joint not in _HEAD_JOINTS:
            frp_before[joint] = frp
        else:
            leftovers.append(frp)
    for name, angle in joints.items():
        if name in _HEAD_JOINTS:
            continue
        frp = frp_before.get(name)
        if frp is not None:
            out.append(_write_force_resistance(frp))
        out.append("(HJ (n %s) (ax %.2f))" % (name, angle))  # noqa: UP031
    out.extend(_write_force_resistance(frp) for frp in leftovers)
    return "".join(out).encode("ascii")
