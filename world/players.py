"""Other robots as vision reports them: teammates and opponents on the field.

Vision names a robot by team and uniform number and gives polars of up to five body parts
(head, lower arms, feet). The world model turns those into team-frame positions; here they
become one :class:`PlayerObservation` per robot, remembered with the time it was last seen.
A robot's place on the field is the middle of its feet when both are seen (where it stands),
else the mean of whatever parts are seen; its head's height tells whether it is standing.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

__all__ = ["FALLEN_HEAD_HEIGHT", "PlayerObservation", "PlayerTracker"]

#: A robot whose head centre is lower than this (m) is lying on the ground (standing: ~0.5 m).
FALLEN_HEAD_HEIGHT = 0.3

Vec3 = tuple[float, float, float]


@dataclass(slots=True)
class PlayerObservation:
    """What the agent last saw of one robot. Positions are in the team frame (m)."""

    team: str
    unum: int
    #: where the robot stands: middle of its feet, else the mean of its seen parts (x, y)
    position: tuple[float, float]
    #: body part name -> (x, y, z) in the team frame, as last seen
    parts: dict[str, Vec3] = field(default_factory=dict)
    last_seen: float = 0.0

    @property
    def is_fallen(self) -> bool | None:
        """Whether the robot lies on the ground (None when its head was not seen)."""
        head = self.parts.get("head")
        return None if head is None else head[2] < FALLEN_HEAD_HEIGHT

    def age(self, now: float) -> float:
        """Seconds since this robot was last seen."""
        return now - self.last_seen


def _standing_point(parts: Mapping[str, Vec3]) -> tuple[float, float]:
    # plain floats and no generators: this runs for every robot in every image
    left, right = parts.get("lfoot"), parts.get("rfoot")
    if left is not None and right is not None:
        return ((left[0] + right[0]) / 2, (left[1] + right[1]) / 2)
    x = y = 0.0
    for p in parts.values():
        x += p[0]
        y += p[1]
    return (x / len(parts), y / len(parts))


class PlayerTracker:
    """The robots of one team as last seen, keyed by uniform number."""

    def __init__(self) -> None:
        self.players: dict[int, PlayerObservation] = {}

    def observe(self, team: str, unum: int, parts: Mapping[str, Vec3], time: float) -> None:
        """Record one sighting (parts in the team frame); empty sightings are ignored."""
        if not parts:
            return
        self.players[unum] = PlayerObservation(
            team=team,
            unum=unum,
            position=_standing_point(parts),
            parts=dict(parts),
            last_seen=time,
        )

    def recent(self, now: float, max_age: float = 2.0) -> list[PlayerObservation]:
        """Robots seen within ``max_age`` seconds, by uniform number."""
        return [p for _, p in sorted(self.players.items()) if now - p.last_seen <= max_age]

    def nearest(
        self, point: tuple[float, float], now: float, max_age: float = 2.0
    ) -> PlayerObservation | None:
        """The recently seen robot standing closest to ``point``."""
        candidates = self.recent(now, max_age)
        if not candidates:
            return None
        return min(
            candidates,
            key=lambda p: (p.position[0] - point[0]) ** 2 + (p.position[1] - point[1]) ** 2,
        )

    def forget(self, unums: Iterable[int] | None = None) -> None:
        """Drop some (or all) remembered robots."""
        if unums is None:
            self.players.clear()
        else:
            for unum in unums:
                self.players.pop(unum, None)

    def __len__(self) -> int:
        return len(self.players)

    def __iter__(self):
        return iter(self.players.values())

    def __getitem__(self, unum: int) -> PlayerObservation:
        return self.players[unum]

    def __contains__(self, unum: object) -> bool:
        return unum in self.players
