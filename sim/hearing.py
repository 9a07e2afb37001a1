"""Who hears which ``say`` message: the real server's audio rules.

rcssserver3d (SoccerRuleAspect::Broadcast, AgentState, HearPerceptor) does not deliver every
message to everyone. Each listener has a hearing *capacity* per team, 2 units at most: a message
of a teammate (or of an opponent) is heard only while that team's capacity is at least 2, and
hearing it costs 2; every perception gives 1 unit back. So a listener hears at most one teammate
and one opponent message per cycle, and after hearing one it is deaf to that team for the next
cycle. When several players speak in the same cycle, the first one in the server's order (the
order the agents connected) is heard and the others are lost. The speaker always hears itself.
Messages reach listeners within 50 m (``HEAR_DISTANCE``).

The direction of a message is the horizontal angle (degrees) from the listener to the speaker
in the listener's team's field frame (the real server flips the view for the right team), not
relative to where the listener faces.

A team that wants its messages heard must therefore take turns (see ``agent.roles``): at most
one speaker per cycle, and a cycle of silence between messages.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from world.perception import Heard

#: Largest hearing capacity per team (AgentState::mHearMax).
HEAR_MAX = 2
#: Capacity given back by every perception (mHearInc).
HEAR_INC = 1
#: Capacity one heard message costs (mHearDecay).
HEAR_DECAY = 2
#: Messages travel this far (SoccerRuleAspect::mAudioCutDist, metres).
HEAR_DISTANCE = 50.0


@dataclass
class _Message:
    team: str
    direction: float
    text: str


@dataclass
class _Channel:
    """What a listener hears of one team (its own, or the opponents'): the capacity and the
    message waiting for the next perception."""

    capacity: int = HEAR_MAX
    waiting: _Message | None = field(default=None, repr=False)

    def offer(self, message: _Message) -> None:
        if self.capacity < HEAR_DECAY:
            return
        self.capacity -= HEAR_DECAY
        self.waiting = message

    def take(self, game_time: float) -> list[Heard]:
        """The waiting message, if any; every call (one per perception) gives capacity back."""
        self.capacity = min(HEAR_MAX, self.capacity + HEAR_INC)
        message, self.waiting = self.waiting, None
        if message is None:
            return []
        return [Heard(message.team, game_time, message.direction, message.text)]


@dataclass
class Ear:
    """One listener's hearing state: a channel per team and its own message."""

    own: str | None = None
    mate: _Channel = field(default_factory=_Channel)
    opponent: _Channel = field(default_factory=_Channel)

    def offer(self, message: _Message, teammate: bool) -> None:
        """A message reaches this listener; it is kept only if the capacity allows."""
        (self.mate if teammate else self.opponent).offer(message)

    def take(self, own_team: str, game_time: float) -> list[Heard]:
        """The ``hear`` entries of this cycle's perception (own, teammate, opponent, as the
        real HearPerceptor writes them); every call gives capacity back."""
        heard = []
        if self.own is not None:
            heard.append(Heard(own_team, game_time, "self", self.own))
            self.own = None
        return heard + self.mate.take(game_time) + self.opponent.take(game_time)


@dataclass(frozen=True)
class Listener:
    """What the broadcast needs to know of one agent on the field."""

    ear: Ear
    team: str
    side: str
    x: float
    y: float


def broadcast(speakers: list[tuple[Listener, str]], listeners: list[Listener]) -> None:
    """Deliver one cycle's ``say`` messages, in the order given (the server's agent order)."""
    for speaker, text in speakers:
        speaker.ear.own = text
        for listener in listeners:
            if listener is speaker:
                continue
            dx, dy = speaker.x - listener.x, speaker.y - listener.y
            if math.hypot(dx, dy) > HEAR_DISTANCE:
                continue
            if listener.side == "right":
                dx, dy = -dx, -dy
            direction = math.degrees(math.atan2(dy, dx))
            message = _Message(speaker.team, direction, text)
            listener.ear.offer(message, teammate=listener.team == speaker.team)
