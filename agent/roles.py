"""Who goes for the ball: claims said aloud and heard by teammates.

Vision alone cannot settle it: a player sees only the teammates inside its 120 deg view cone,
so players that see no closer teammate all believe themselves closest and the whole team runs
to the ball. Each player therefore says its claim on the ball (its distance to it, in
decimetres) in a short message, and the player with the lowest recent claim goes.

Message format (``say``, at most 20 printable characters without spaces or parentheses):
``nb<unum>c<decimetres>``, e.g. ``nb7c42``: player 7 is 4.2 m from the ball. Messages of the
other team are ignored (the hear perceptor names the speaker's team).

Players take turns to speak (:func:`my_turn_to_speak`). The real server lets a listener hear at
most one teammate message per cycle, the first one said, and after hearing one it is deaf to its
team for a cycle (``sim.hearing`` has the rules): if everybody spoke every cycle, everybody
would hear only the player the server lists first. So a team speaks every second cycle, one
player per turn in uniform-number order: each player is heard every 22 cycles (0.44 s), well
within :data:`CLAIM_MEMORY_S`.

Tried in session 9, not kept: a player also counting the claim it last said (the one its
teammates compare with) until its next turn, so that a fresh claim compared with a stale one
cannot leave nobody going (``scripts/attack/roles_probe.py --seed 1``: 14-18 s of 120 with no
active player though one was up and saw the ball; never two active for more than 1 s). 3 v 3,
120 s (``benchmarks/match.py --players 3 --matches 8 --duration 120 --seed 1`` / ``--seed 9``):
2 goals 95 falls / 2 goals 94 falls, against 2 / 119 and 4 / 104 without it (with the
supporter on); on the final checkout of session 9 (supporter off) 2 goals 108 falls / 2 goals
87 falls, against 2 / 93 and 4 / 94 without it.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from world.perception import CYCLE_SECONDS

#: A claim older than this (s) no longer counts: its speaker went quiet (lost the ball, left).
CLAIM_MEMORY_S = 1.0
#: Largest claim that fits the message (decimetres).
MAX_CLAIM_DM = 9999

#: Cycles between two messages of the team: a listener's capacity needs two to recover.
TURN_CYCLES = 2
#: Uniform numbers that take turns (a full team; the turns of absent players stay silent).
TEAM_SIZE = 11

_CLAIM = re.compile(r"^nb(\d{1,2})c(\d{1,4})$")


def claim_message(unum: int, claim_m: float) -> str:
    """The ``say`` text for player ``unum`` claiming ``claim_m`` metres."""
    decimetres = min(MAX_CLAIM_DM, max(0, round(claim_m * 10.0)))
    return f"nb{unum}c{decimetres}"


def my_turn_to_speak(unum: int, server_time: float) -> bool:
    """Whether player ``unum`` may speak in the cycle of the perception stamped
    ``server_time``: every player of the team computes the same turns from the shared clock."""
    cycle = round(server_time / CYCLE_SECONDS)
    if cycle % TURN_CYCLES:
        return False
    return (cycle // TURN_CYCLES) % TEAM_SIZE == (unum - 1) % TEAM_SIZE


def parse_claim(message: str) -> tuple[int, float] | None:
    """``(unum, metres)`` from a claim message, or None for any other message."""
    match = _CLAIM.match(message)
    if match is None:
        return None
    return int(match.group(1)), int(match.group(2)) / 10.0


@dataclass(frozen=True)
class Claim:
    claim_m: float
    time: float


class ClaimBoard:
    """The latest claim heard from each teammate."""

    def __init__(self) -> None:
        self.claims: dict[int, Claim] = {}

    def hear(self, world) -> None:
        """Take this cycle's heard messages from the world model (own team only; the own
        message, heard back as ``self``, is skipped)."""
        team = getattr(world, "team_name", None)
        for heard in getattr(world, "heard", ()):
            if heard.direction == "self" or (team is not None and heard.team != team):
                continue
            parsed = parse_claim(heard.message)
            if parsed is not None and parsed[0] != world.unum:
                self.claims[parsed[0]] = Claim(parsed[1], world.time or 0.0)

    def has(self, unum: int, now: float) -> bool:
        """Whether ``unum`` made a claim within :data:`CLAIM_MEMORY_S`."""
        claim = self.claims.get(unum)
        return claim is not None and now - claim.time <= CLAIM_MEMORY_S

    def recent(self, now: float) -> dict[int, float]:
        """Claims made within :data:`CLAIM_MEMORY_S`, by unum."""
        return {
            unum: claim.claim_m
            for unum, claim in self.claims.items()
            if now - claim.time <= CLAIM_MEMORY_S
        }


def is_closest(board: ClaimBoard, unum: int, claim_m: float, now: float) -> bool:
    """Whether player ``unum`` claiming ``claim_m`` wins against the recent claims heard
    (ties go to the lower unum: every player decides the same way). The own claim is rounded
    as the message rounds it, so that both sides of a comparison see the same numbers."""
    mine = parse_claim(claim_message(unum, claim_m))
    own = claim_m if mine is None else mine[1]
    return all(
        (own, unum) < (other, other_unum)
        for other_unum, other in board.recent(now).items()
        if other_unum != unum
    )
