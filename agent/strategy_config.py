"""The strategy's settings: formation places, attacking, support, advancing, keeping, read
from a team's YAML file (``config/team.yaml`` spells out every default) and validated there.

Why a module of its own: the settings are read, checked and documented (each with the figures
that set its default) apart from the decisions that use them (:mod:`agent.strategy`); a
reader tuning a team needs this file and ``config/team.yaml``, not the decision code.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from world.yaml_config import load_yaml_config


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

    #: shoot with ``basic_kick`` once the ball is this close to the goal centre (0: never,
    #: dribble it in; without a dribble skill it always kicks) ... 6 m: the long kick goes
    #: about 6.3 m within a few degrees of its aim (session 30), and a shot from outside the
    #: goalkeeper's reach scored where the dribble into the keeper stalled (3 v 3 figures in
    #: config/team.yaml)
    kick_range_m: float = 6.0
    #: ... and a shot under way goes on while the ball stays within ``kick_range_m`` plus
    #: this (hysteresis). Why: the ball's estimate jitters by centimetres, and an attacker that
    #: brought the ball to the edge of the range switched between the shot's approach and the
    #: dribble up to seven times in three seconds, each switch restarting both skills (session
    #: 32, ``python scripts/attack/shot_probe.py --players 3 --matches 4 --seed 1``: 13 of 19
    #: shots ended within a second in their approach, 4 kicked; figures in config/team.yaml)
    kick_range_hold_m: float = 1.0
    #: ... but no range shot starts, and one still lining up (before its head-up and kick) ends,
    #: while an opponent is within this of the ball (0: off): the basic kick stands 5-12 s
    #: at the ball, and in 11 v 11 a defender reached it in that time in every shot (session
    #: 32, ``scripts/attack/shot_probe.py --players 11``); the dribble goes on instead. Off:
    #: with 1.0 (``--set strategy.attack.shot_contest_m=1.0``) 11 v 11 seeds 4 / 5 started 5 /
    #: 2 shots against 1 / 3, none kicked either way, 0-0 in all four matches (sessions 33-34)
    shot_contest_m: float = 0.0
    #: ... but closer than this, walk it in with the dribble (surer than a kick that falls)
    dribble_in_m: float = 2.5
    #: the approach point lies this far behind the ball on the line goal -> ball
    behind_ball_m: float = 0.3
    #: start dribbling within this distance of the approach point ...
    dribble_start_m: float = 0.25
    #: ... facing the goal within this angle
    dribble_align_deg: float = 25.0
    #: keep dribbling while the ball stays within this distance of the torso (also: a player
    #: this close to a ball that stays put counts as stalled at it). 1.2, not 0.7: an LFDL
    #: stride pushes the ball up to about 1.3 m ahead, and the dribble follows such a ball at
    #: its 0.9 m/s (``beyond_reach_speed``), while ``walk`` back to the approach point starts
    #: from its first step at the 0.65 m/s cap and slows down at the point, long enough for a
    #: keeper or defender to reach the ball first. 3 v 3, 120 s (benchmarks/match.py
    #: --players 3 --matches 1 --duration 120 --seed S): S = 1-8 4 goals, 97 falls (0.7: 0
    #: goals, 123 falls); S = 9-16 3 goals, 97 falls (0 goals, 148 falls); after session 8's
    #: walk change for type 2 was merged: 1 and 4 goals, 92 and 93 falls
    dribble_keep_m: float = 1.2
    #: stop dribbling when the ball is this close to the torso: the robot is over it (it
    #: can no longer see it, and standing on it draws the ball-holding foul)
    dribble_min_m: float = 0.12
    #: which dribble gait: "dfdl" or "lfdl". LFDL: it walks at full speed with the ball further
    #: ahead (benchmarks/attack.py --trials 3: median 31.1 s to the goal, against 57.8 s with
    #: ``--set strategy.attack.dribble_kind=dfdl``)
    dribble_kind: str = "lfdl"
    #: within ``near_goal_dribble_m`` of the opponent goal centre dribble with this gait
    #: instead ("": the same gait everywhere). Why: LFDL's strides push the ball up to a
    #: metre ahead, the player falls back to walking after it, and a keeper that comes out
    #: meets the loose ball first; DFDL keeps it closer, slower
    near_goal_dribble_kind: str = ""
    near_goal_dribble_m: float = 5.0
    #: a player not behind the ball goes round it, passing this far to its side
    round_ball_m: float = 0.5
    #: aim this far from the goal centre, on the side away from a goalkeeper standing within
    #: ``keeper_near_m`` of the goal centre (0: always aim at the centre). 0.4 (session 32):
    #: alone against the keeper (benchmarks/attack.py --trials 10 --seconds 60 --keeper, seeds
    #: 0 / 100) 9 / 8 of 10 goals against 6 / 7, but 3 v 3 (benchmarks/match.py --players 3
    #: --matches 8 --duration 120 --seed 1 / 9) 11 / 10 goals, 7 / 8 of 8 matches, against
    #: 9 / 14 and 8 / 8 at 0.6
    aim_side_m: float = 0.6
    keeper_near_m: float = 2.5
    #: with the ball this close to the opponent goal line (m) and in front of the goal mouth
    #: (``finish_post_margin_m`` inside the posts), aim straight over the line instead of at
    #: the aim point on it (0: never). Why: the aim points lie ON the goal line, so as the
    #: ball nears it the line to the aim turns sideways; a ball 0.16 m before the line and
    #: 0.8 m off the middle was dribbled towards the far post, across the goal mouth, until
    #: the keeper came back (``benchmarks/attack.py --keeper --trials 1 --seconds 40
    #: --start-x 9 --trace 1``)
    finish_m: float = 1.5
    finish_post_margin_m: float = 0.1
    #: in that finishing zone a stall shot (``stall_shot_m``) ends and none starts: the ball is
    #: pushed straight over the line by the dribble. Why: a keeper beside the ball 0.7-1.6 m
    #: before the line kept ``basic_kick`` lining up for 8 s while it walked round the ball
    #: and cleared it (``python scripts/attack/match_probe.py --players 3 --seed 3 --window
    #: 55 80``). Off: over 32 3 v 3 matches (``benchmarks/match.py --seed 1`` / ``--seed 17``)
    #: 11 goals against 10, 30 matches alike (docs/tuning-history.md, session 18)
    finish_no_shot: bool = False
    #: aim ``aim_post_margin_m`` inside the post of the side that the keeper (as above)
    #: leaves most open as seen from the ball (:func:`agent.attack_keeper.open_side`), kept
    #: until the other side is better by ``aim_switch_deg`` (0: the rule of ``aim_side_m``)
    aim_post_margin_m: float = 0.0
    aim_switch_deg: float = 10.0
    #: an opponent less than ``detour_ahead_m`` ahead of the ball and ``detour_clear_m``
    #: beside the line to the aim makes the player take the ball to the point level with it
    #: and ``detour_clear_m`` to its side (:func:`agent.attack_keeper.detour_point`),
    #: instead of the dodge's fixed turn (0: off, the dodge below)
    detour_clear_m: float = 0.0
    detour_ahead_m: float = 2.0
    #: count a stall only while dribbling: walking round a ball that lies still is no stall
    #: (otherwise a player lining up near the goal starts the slow stall shot at a free ball)
    stall_only_dribbling: bool = False
    #: count a stall only with an opponent this close to the ball (m; 0: any stall). Why: a
    #: ball lying still while this player walks up to it is no duel, yet within 4 s of the
    #: goal it started the slow stall shot (``basic_kick`` lining up for 6 s and more) at a
    #: free ball 1.2 m before an empty goal, and the keeper came back and took it
    #: (``benchmarks/attack.py --keeper --trials 1 --seconds 40 --start-x 9 --trace 1``)
    stall_opponent_m: float = 1.0
    #: an opponent within ``yield_opponent_m`` of the ball on its far side while this player
    #: is within ``yield_reach_m`` of it (:func:`agent.attack_keeper.contested`) makes the
    #: player stop and step in place for up to ``yield_s``, instead of walking into the ball
    #: against it; then it plays on for at least ``yield_s`` before it yields again (0 m: off)
    yield_opponent_m: float = 0.0
    yield_reach_m: float = 0.6
    yield_s: float = 2.0
    #: when the ball has moved less than ``stall_m`` in ``stall_s`` of going for it (two
    #: players pushing it against each other), take it ``escape_deg`` off the line to the
    #: aim, towards the side of fewer opponents, for ``escape_s`` (0 s: never)
    stall_s: float = 4.0
    #: ... except within this distance of the goal centre (a keeper or defender blocking
    #: the way in), where a stall is answered with ``basic_kick`` at the goal instead
    stall_shot_m: float = 4.0
    #: ... and only with the ball within this of the goal's centre line (|y|, 0: any y); a
    #: stall wider out is escaped for ``escape_s`` by dribbling towards the point
    #: ``stall_centre_back_m`` in front of the goal centre. Why: a stall shot from beside the
    #: goal (benchmarks/attack.py --trials 2 --trace 4: ball at x 13, y 1.6-2.4) has no angle
    #: and ``basic_kick`` lined up there fell three times in four
    stall_shot_max_y_m: float = 0.0
    stall_centre_back_m: float = 2.0
    #: a stall shot that has not finished after this long (s) is given up for an escape: a
    #: keeper at the ball keeps ``basic_kick`` lining up for ever (0: never give up)
    shot_max_s: float = 8.0
    stall_m: float = 0.35
    escape_deg: float = 70.0
    escape_s: float = 3.0
    #: taking the team's kick-off, and for ``kickoff_turn_s`` after it, aim this far (deg) off
    #: the line to the goal, away from the opponents within ``kickoff_clear_m`` of the ball (0:
    #: off). Why: the other team waits outside the centre circle straight ahead, on the far
    #: side of the ball, which is where its approach to the ball ends; a taker dribbling
    #: straight at it handed it the ball (3 v 3, the team taking the first kick-off scored 15
    #: of the 47 goals of session 32's final runs). Off: with 45, 3 v 3 (benchmarks/match.py
    #: --players 3 --matches 8 --duration 120 --seed S, S = 1 / 9 / 17 / 25) 16 / 13 / 10 / 12
    #: goals (32 of the 51 by the kick-off team), 7 / 7 / 7 / 7 of 8 matches with a goal,
    #: against 9 / 14 / 12 / 12 goals and 8 / 8 / 8 / 7 off: more goals, more goalless matches
    kickoff_turn_deg: float = 0.0
    kickoff_turn_s: float = 4.0
    kickoff_clear_m: float = 4.0
    #: an opponent within ``dodge_ahead_m`` ahead of the ball and ``dodge_across_m`` of the
    #: dribble line turns the dribble ``dodge_deg`` away from it (0: never)
    dodge_ahead_m: float = 1.8
    dodge_across_m: float = 0.7
    dodge_deg: float = 35.0
    #: dribble into free space instead of the dodge (0 deg: off, the dodge): an opponent
    #: within ``free_space_clear_m`` of the path ``free_space_ahead_m`` ahead of the ball
    #: turns the dribble by the fewest ``free_space_step_deg`` steps, at most
    #: ``free_space_deg``, that make the path free (:func:`agent.attack_keeper.free_heading`).
    #: Why: most 11 v 11 falls were the two active players' at the ball, both dribbling into
    #: each other. 60 deg, 11 v 11 120 s (``scripts/attack/match_probe.py --players 11 --seed
    #: S --duration 120``): seeds 1-4 2 goals, 39 falls (off: 0, 47); seeds 5-8 0 goals, 44
    #: falls (off: 0, 54); 3 v 3 seeds 1-8 4 goals, 95 falls (off: 5, 89), see
    #: :attr:`StrategyConfig.free_space_min_players`. Off since the merge: on the merged
    #: checkout seeds 1-4 gave 0 goals, 61 falls with it against 2 goals, 46 falls without
    free_space_deg: float = 0.0
    free_space_step_deg: float = 15.0
    free_space_ahead_m: float = 2.0
    free_space_clear_m: float = 0.8
    #: the ball within ``hold_guard_m`` of the torso for ``hold_guard_s`` (with gaps shorter
    #: than the referee's 0.5 s reset) makes the player step back for ``back_off_s``: the
    #: referee calls holding at 5 s within 0.12 m, and pushing the ball against an opponent
    #: keeps it that close (0 s: never)
    hold_guard_m: float = 0.15
    hold_guard_s: float = 3.0
    back_off_s: float = 1.0
    #: a snap shot: with the ball within ``snap_range_m`` of the goal centre, lying within
    #: ``snap_along_m`` / ``snap_across_m`` of where a foot's stand kick wants it and the
    #: robot facing into the goal mouth (the heading's line crossing the goal line at least
    #: ``snap_post_margin_m`` inside the posts), the player kicks at once with the stand kick
    #: at full strength instead of dribbling on into the keeper or lining up ``basic_kick``
    #: (0: never). Why: ``basic_kick`` takes about 10 s to line up, long enough for the
    #: keeper to come out and stop the ball; the LFDL dribble carries the ball about 6 cm
    #: beyond the left foot's kick spot, so a loose ``snap_along_m`` takes it mid-dribble.
    #: Before the kick the robot stops (``walk_velocity`` 0 for ``snap_stop_s``, then the
    #: stand pose for ``snap_stand_s``) and kicks only if the ball still lies at the spot:
    #: kicked straight out of the walk, it fell (benchmarks/attack.py --keeper --trace 1.5)
    snap_range_m: float = 0.0
    snap_along_m: float = 0.08
    snap_across_m: float = 0.04
    snap_post_margin_m: float = 0.2
    snap_stop_s: float = 0.4
    snap_stand_s: float = 0.5
    #: a stop that ended with the ball off the spot starts no new snap shot for this long (s):
    #: otherwise the dribble nudges the ball back and the player stops again, creeping on
    #: in stops while the keeper comes out (lead: 3 s of stops, attack.py --keeper --trace)
    snap_retry_s: float = 3.0
    #: sprint: an approach point farther than this (m) is walked to with ``walk_velocity`` at
    #: full speed, steering towards it, instead of ``walk`` to the point (0: never). Why:
    #: ``walk`` to a target is capped at 0.65 m/s and lands its steps flat (the full-speed
    #: heel strike tripped it in turns); straight ahead it covers 6 m at 0.46-0.50 m/s
    #: against 0.76-0.83 m/s for ``walk_velocity`` (every robot type), so the active player
    #: reached a ball 7 m away in 15 s of an 11 v 11 match. ``walk`` takes over again for
    #: the last ``sprint_m`` metres, where it slows down and turns to face the aim. Off by
    #: default: 3 v 3 matches (config/team.yaml) did not score more with it
    sprint_m: float = 0.0
    #: ... at this forward command (m/s; the walk's top speed is 0.80-0.88 m/s, and at the
    #: full 1.0 command sprints that started from a turning ``walk`` fell more) ...
    sprint_speed_m_s: float = 0.85
    #: ... starting only with the point within this angle of the torso's heading (deg) and
    #: stopping beyond ``sprint_stop_deg`` ...
    sprint_start_deg: float = 10.0
    sprint_stop_deg: float = 45.0
    #: ... steering with this turn rate per degree of heading error (deg/s per deg, capped
    #: at ``sprint_max_turn_deg_s``: turning 20-30 deg/s at full speed tripped the robot)
    sprint_turn_gain: float = 1.0
    sprint_max_turn_deg_s: float = 10.0
    #: walking to the approach point, a robot (either team, as vision last saw it) standing
    #: within this of the straight way is walked round, this far to its side (0: walk
    #: straight through; :func:`agent.avoidance.avoidance_waypoint`). 0.8: 3 v 3 goals 5 -> 12
    #: in 32 matches, falls a little fewer (figures in ``config/team.yaml``) ...
    avoid_clear_m: float = 0.8
    #: ... unless it stands within this of the approach point (a contest for the ball) ...
    avoid_target_zone_m: float = 0.6
    #: ... by way of a point this far past it along the way
    avoid_beyond_m: float = 0.3

    def __post_init__(self) -> None:
        if not 0.0 <= self.free_space_deg <= 180.0:
            raise ValueError(f"free_space_deg must be 0-180, got {self.free_space_deg}")
        if self.free_space_deg > 0.0 and not 0.0 < self.free_space_step_deg <= 90.0:
            raise ValueError(
                f"free_space_step_deg must be in (0, 90], got {self.free_space_step_deg}"
            )


@dataclass(frozen=True)
class SupportConfig:
    """Where the second field player (the next-lowest claim after the active player) waits
    for a loose ball: ``ahead_m`` beyond the ball towards the opponent goal and ``side_m`` to
    one side of the dribble line (so it does not stand in the dribbler's way), only while the
    ball is in the opponent half beyond ``from_x_m``, and stepping in place while an opponent
    stands in its way (``avoid_m``). ``ahead_m`` 0 and ``side_m`` 0: no support, it holds its
    formation place. Off by default. On the attack branch of session 9 (ahead 2.0, side 1.5,
    from 3 m, avoid 1 m) 3 v 3, 120 s (benchmarks/match.py --players 3 --matches 8 --duration
    120 --seed 1 and --seed 9) gave seeds 1-8 2 goals, 119 falls (off: 0, 100), seeds 9-16 4
    goals, 104 falls (off: 3, 108); on the merged checkout (with session 9's walk and get-up)
    the same commands gave 1 goal, 1.05 falls per player-minute and 1 goal, 1.08 against 2
    goals, 0.97 and 4 goals, 0.98 with it off, so it stays off (--set strategy.support.ahead_m=2
    --set strategy.support.side_m=1.5 to try it). Everywhere (``from_x_m`` -15, no
    ``avoid_m``) it fell more: seeds 1-8 2 goals, 140 falls; from 3 m without ``avoid_m`` 3
    goals, 136 falls."""

    ahead_m: float = 0.0
    side_m: float = 0.0
    #: it stays at least this far from the opponent goal line and the touch lines
    margin_m: float = 1.0
    #: it supports only while the ball lies at least this far up the field (team frame x;
    #: -15: everywhere; 3: the opponent half beyond the centre circle); short of it, it holds
    #: its formation place. Why: a
    #: supporter near a duel in midfield or the own half walks into it (more falls), while
    #: near the opponent goal it can take the ball a goalkeeper wins off the active player
    from_x_m: float = 3.0
    #: on its way it stops (steps in place) while an opponent stands within this (m) of it in
    #: the direction it walks (within 60 deg): a supporter crossing the field walked into
    #: opponents holding their places, far from the ball (falls; 0: never stops)
    avoid_m: float = 1.0


@dataclass(frozen=True)
class AdvanceConfig:
    """Field players that move up with the ball as second attackers (``unums``, full-team
    uniform numbers; empty: off). While the ball lies beyond ``from_x_m`` (team frame), such a
    player's place is ``behind_m`` behind the ball (x in steps of ``step_m``, at most
    ``max_x_m``, never behind its formation place), ``y_m`` from the middle on its own side,
    and at least ``clear_m`` from the ball; on its way it steps in place while an opponent
    stands within ``avoid_m`` in its way. Why: in 11 v 11 the active forward attacked the
    goal alone, its nearest teammate 14-15 m back at its formation place (``python
    scripts/attack/match_probe.py --players 11 --seed 1``: the ball 58 s of 120 beyond x = 7.5,
    the forward falling in duels there), so a ball it lost went to a defender; an advanced
    teammate is the nearest claim for such a loose ball and takes it over. Off: with
    ``unums`` (9, 11) seeds 1-3 (the same command, ``--set "strategy.advance.unums=[9,
    11]"``) gave 1 goal, 57 falls against 1 goal, 43 falls (advancing wingers stepping in
    place among the defenders were knocked over, and more players met at the ball)."""

    unums: tuple[int, ...] = ()
    from_x_m: float = 2.0
    behind_m: float = 1.0
    y_m: float = 2.5
    max_x_m: float = 13.0
    clear_m: float = 1.5
    step_m: float = 1.0
    avoid_m: float = 1.0


@dataclass(frozen=True)
class KeeperConfig:
    """Where the goalkeeper stands and when it leaves its line (team frame, metres)."""

    #: distance in front of the own goal line where it guards
    line_offset_m: float = 0.7
    #: it follows the ball sideways by this fraction of the ball's y ...
    follow_fraction: float = 0.35
    #: ... up to this far from the centre
    max_side_m: float = 0.8
    #: it goes for the ball only while the ball is within this distance of the own goal
    #: centre (and it is the team's closest player)
    clear_range_m: float = 4.0
    #: its place's y moves in steps of this (m; 0: follows the ball smoothly), and it faces
    #: the ball in steps of :data:`agent.strategy.HOLD_HEADING_STEP_DEG` as the field players
    #: do. Why: a
    #: place and heading that followed every move of a ball far away kept the keeper
    #: shuffling and turning on the spot, and it fell backwards doing so with the ball 12 m
    #: away (``scripts/attack/match_probe.py --seed 2 --window 74 81``). Off: with 0.2 the
    #: keepers of 3 v 3 seeds 1-8 (match_probe.py --seed S, S = 1 ... 8) fell 14 times
    #: against 18, but all players 83 against 77, and 1 goal against 2
    side_step_m: float = 0.0


@dataclass(frozen=True)
class StrategyConfig:
    """Formation places (unum -> x, y in the team frame), attacking and goalkeeping; see
    ``config/team.yaml``."""

    formation: dict[int, tuple[float, float]] = field(default_factory=_default_formation)
    attack: AttackConfig = field(default_factory=AttackConfig)
    keeper: KeeperConfig = field(default_factory=KeeperConfig)
    support: SupportConfig = field(default_factory=SupportConfig)
    advance: AdvanceConfig = field(default_factory=AdvanceConfig)
    #: places held during play instead of the formation's (unum -> x, y; empty: the
    #: formation's); the formation place stays the beam place before a kick-off. Why: the
    #: two centre forwards' places (the kick-off taker's, x -0.6) lie 1.2 m apart, and a
    #: forward walking back to its place fell there against the other again and again, the
    #: ball 5-14 m away (``python scripts/attack/match_probe.py --players 11 --seed 3``: the
    #: right team's 10 six times)
    play_places: dict[int, tuple[float, float]] = field(default_factory=dict)
    #: a field player that does not go for the ball waits at least this far from it (m; its
    #: place moved away from the ball along the line through both; 0: off). Why: defenders
    #: holding their places at their own goal stood in the duel there and fell with the
    #: active teammate, and the next of them to go fell into the same pile (``python
    #: scripts/attack/match_probe.py --players 11 --seed 1 --set
    #: "strategy.play_places={10: [-2.5, 0.0]}"``: the right team's 4, 5 and 7 fell nine
    #: times with a teammate within 1.2 m, the ball 85 s of 120 beyond x = 7.5). Off: 1.5
    #: cut 11 v 11 falls by a fifth (seeds 1-4 45 against 57, 5-8 47 against 63, goals 0
    #: against 1 and 1 against 0) but 3 v 3 scored less (see config/team.yaml)
    hold_clear_m: float = 0.0
    #: ... but only in a team of at least this many players (the places of
    #: :attr:`formation`; 0: any team). Why: keeping clear cut the falls of 11 v 11 but cost
    #: 3 v 3 goals (see :attr:`hold_clear_m`), and a smaller team's formation lists only the
    #: places it fields (``benchmarks.match.small_team``), so a team knows its size from it.
    #: Session 14 (after session 13's merge) 11 v 11 with 1.5 m and 11 players, seeds 1-3:
    #: 52 falls and 1 goal against 38 and 0 off, so both stay off (config/team.yaml)
    hold_clear_min_players: int = 0
    #: dribble into free space (:attr:`AttackConfig.free_space_deg`) only in a team of at
    #: least this many players (0: any team), the dodge in a smaller one: it cut falls and
    #: scored in 11 v 11 but not in 3 v 3 (config/team.yaml)
    free_space_min_players: int = 11
    #: the goalkeeper's unum (it guards its goal instead of attacking); None: no goalkeeper
    goalie_unum: int | None = 1

    def __post_init__(self) -> None:
        if self.hold_clear_m < 0.0:
            raise ValueError(f"hold_clear_m must be >= 0, got {self.hold_clear_m}")
        for name in ("hold_clear_min_players", "free_space_min_players"):
            if not 0 <= getattr(self, name) <= 11:
                raise ValueError(f"{name} must be 0-11, got {getattr(self, name)}")

    @property
    def hold_clear(self) -> float:
        """The clearance (m) a waiting field player keeps from the ball in this team
        (:attr:`hold_clear_m`, or 0 in a team smaller than :attr:`hold_clear_min_players`)."""
        if len(self.formation) < self.hold_clear_min_players:
            return 0.0
        return self.hold_clear_m

    @property
    def free_space_deg(self) -> float:
        """:attr:`AttackConfig.free_space_deg`, or 0 (the dodge) in a team smaller than
        :attr:`free_space_min_players`."""
        if len(self.formation) < self.free_space_min_players:
            return 0.0
        return self.attack.free_space_deg

    @classmethod
    def from_yaml(cls, path: str | Path) -> StrategyConfig:
        return load_yaml_config(cls, path)
