"""Typed perceptions: what one server message tells an agent.

The classes here are the contract between the codec (parsing and writing the wire format), the
server's perceptor generation and the agent's world model. Angles are degrees, distances metres,
as on the wire.
"""

from __future__ import annotations

from dataclasses import dataclass, field


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
