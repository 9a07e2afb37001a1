"""The strategy layer: formation, beam before kick-off, roles, and which behaviour runs when.

Kept deliberately small: it decides, behaviours act. Each cycle :meth:`Strategy.decide` reads
the world model (perception-fed only) and calls ``Behavior.execute`` with the chosen skill.
Positions are in the team frame: x towards the opponent goal, own goal at x = -15.

Roles: the player that believes itself closest to the ball (its own estimate against the
teammates it has seen) is *active* and goes for the ball; the others hold their formation
places. The active player walks to a point behind the ball on the line to the opponent goal,
dribbles towards the goal once there and facing it, and shoots with ``basic_kick`` when the
ball is within kicking range of the goal (:class:`AttackConfig`). A skill that is not
registered is skipped (the player walks or stands instead), so the strategy runs with whatever
skills exist.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from world.field_geometry import HALF_LENGTH
from world.localization import wrap_deg
from world.yaml_config import load_yaml_config

#: Play modes in which the rules allow beaming.
BEAM_MODES = ("BeforeKickOff", "Goal_Left", "Goal_Right")
#: A teammate whose estimate is older than this (s) is not counted in role assignment.
TEAMMATE_MEMORY_S = 3.0


def _default_formation() -> dict[int, tuple[float, float]]:
    """A 4-3-3 style formation for 11 players, team frame (x towards the opponent goal)."""
    return {
        1: (-14.0, 0.0),
        2: (-10.5, -4.0),
        3: (-10.5, 4.0),
        4: (-11.5, -1.5),
        5: (-11.5, 1.5),
        6: (-7.0, -5.0),
        7: (-7.0, 0.0),
        8: (-7.0, 5.0),
        9: (-3.0, -4.5),
        10: (-0.6, 0.0),
        11: (-3.0, 4.5),
    }


@dataclass(frozen=True)
class AttackConfig:
    """How the active player brings the ball to the opponent goal (team frame, metres)."""

    #: shoot with ``basic_kick`` once the ball is this close to the goal centre ...
    kick_range_m: float = 7.0
    #: ... but closer than this, walk it in with the dribble (surer than a kick that falls)
    dribble_in_m: float = 2.5
    #: the approach point lies this far behind the ball on the line goal -> ball
    behind_ball_m: float = 0.3
    #: start dribbling within this distance of the approach point ...
    dribble_start_m: float = 0.25
    #: ... facing the goal within this angle
    dribble_align_deg: float = 25.0
    #: keep dribbling while the ball stays within this distance of the torso
    dribble_keep_m: float = 0.7
    #: which dribble gait: "dfdl" or "lfdl"
    dribble_kind: str = "dfdl"


@dataclass(frozen=True)
class StrategyConfig:
    """Formation places (unum -> x, y in the team frame) and attacking; see
    ``config/team.yaml``."""

    formation: dict[int, tuple[float, float]] = field(default_factory=_default_formation)
    attack: AttackConfig = field(default_factory=AttackConfig)

    @classmethod
    def from_yaml(cls, path: str | Path) -> StrategyConfig:
        return load_yaml_config(cls, path)


@dataclass(frozen=True)
class Decision:
    """What the strategy wants sent besides joint speeds this cycle."""

    beam: tuple[float, float, float] | None = None
    say: str | None = None


def opponents_restart(play_mode: str, side: str | None) -> bool:
    """Whether the opponents are taking a kick-off or set piece: then the rules keep our
    players away from the ball (outside the centre circle, or the free-kick distance)."""
    lower = play_mode.lower()
    if side is None or lower == "playon" or not lower.endswith(("_left", "_right")):
        return False
    return not lower.endswith("_" + side)


class Strategy:
    """Formation, beaming and role assignment for one agent."""

    def __init__(self, config: StrategyConfig | None = None) -> None:
        self.config = config or StrategyConfig()
        self._beamed_in_mode: str | None = None
        self._dribbling = False
        self._getting_up = False

    def decide(self, world, behavior) -> Decision:
        """Pick this cycle's behaviour (through ``behavior.execute``) and any beam."""
        beam = self._beam(world)
        if "get_up" in behavior.skill_names and (world.robot.is_fallen or self._getting_up):
            # once started, the get-up runs until it reports the robot standing: halfway up
            # (sitting, torso 50 deg from vertical) the robot no longer counts as fallen, and
            # walking off from there drops it again
            self._getting_up = not behavior.execute("get_up")
        elif world.play_mode in BEAM_MODES or world.play_mode == "GameOver":
            behavior.execute("pose", "stand")
        elif self.is_active(world) and not opponents_restart(world.play_mode, world.side):
            self._go_for_ball(world, behavior)
        else:
            self._hold_position(world, behavior)
        return Decision(beam=beam)

    # ------------------------------------------------------------------ roles
    def home(self, unum: int | None) -> tuple[float, float]:
        return self.config.formation.get(unum or 0, (-5.0, 0.0))

    def is_active(self, world) -> bool:
        """Closest to the ball among the teammates this agent knows about."""
        ball = world.ball.position
        if ball is None or world.pose is None or world.time is None:
            return False
        mine = math.dist((world.pose.x, world.pose.y), ball)
        return all(
            math.dist(mate.position, ball) >= mine
            for mate in world.teammates.recent(world.time, TEAMMATE_MEMORY_S)
            if mate.unum != world.unum
        )

    # ------------------------------------------------------------------ actions
    def _beam(self, world) -> tuple[float, float, float] | None:
        """Beam once each time a beam-allowed mode starts, to the formation place."""
        if world.play_mode not in BEAM_MODES or world.side is None:
            self._beamed_in_mode = None
            return None
        if self._beamed_in_mode == world.play_mode:
            return None
        self._beamed_in_mode = world.play_mode
        x, y = self.home(world.unum)
        return (x, y, 0.0)

    def _go_for_ball(self, world, behavior) -> None:
        """Shoot when in range, dribble when behind the ball facing the goal, else approach."""
        skills = behavior.skill_names
        if "walk" not in skills or world.pose is None:
            behavior.execute("pose", "stand")
            return
        attack = self.config.attack
        bx, by = world.ball.position
        goal_x, goal_y = HALF_LENGTH, 0.0
        to_goal = math.atan2(goal_y - by, goal_x - bx)
        to_goal_m = math.dist((bx, by), (goal_x, goal_y))
        walk_it_in = "dribble" in skills and to_goal_m < attack.dribble_in_m
        if "basic_kick" in skills and to_goal_m < attack.kick_range_m and not walk_it_in:
            self._dribbling = False
            behavior.execute("basic_kick", goal_x, goal_y, "long")
            return
        pose = world.pose
        approach = (
            bx - attack.behind_ball_m * math.cos(to_goal),
            by - attack.behind_ball_m * math.sin(to_goal),
        )
        facing = abs(wrap_deg(pose.heading_deg - math.degrees(to_goal)))
        if "dribble" in skills:
            near_ball = math.dist((pose.x, pose.y), (bx, by)) < attack.dribble_keep_m
            ready = (
                math.dist((pose.x, pose.y), approach) < attack.dribble_start_m
                and facing < attack.dribble_align_deg
            )
            self._dribbling = ready or (self._dribbling and near_ball)
            if self._dribbling:
                behavior.execute("dribble", attack.dribble_kind, math.degrees(to_goal), "left")
                return
        behavior.execute("walk", approach[0], approach[1], math.degrees(to_goal))

    def _hold_position(self, world, behavior) -> None:
        if "walk" in behavior.skill_names:
            x, y = self.home(world.unum)
            behavior.execute("walk", x, y, 0.0)
        else:
            behavior.execute("pose", "stand")
