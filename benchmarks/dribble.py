"""Dribble benchmark: DFDL and LFDL speed, ball losses, falls, ball distance per phase, holding.

Every run starts as the kick-in-motion episodes do: the robot stands 0.3 m behind the ball at
the field centre, facing the direction to dribble, in PlayOn; then ``dribble(kind, direction,
foot)`` runs until the ball has travelled ``distance`` metres along the direction (or time runs
out). Everything measured is ground truth from the simulator; the skill itself sees only its
perceptions (``learning.local_agent.LocalAgent``).

Definitions (the report's figures mean exactly this):

* speed: ``distance`` divided by the seconds the ball took to get there (0 if it never did);
* a ball loss: the ball gets more than ``LOST_DISTANCE`` (1 m) from the torso along the
  ground, or falls behind the torso; one loss per time it leaves (``max_ball_distance_m`` says
  how far it got at most, for a stricter reading);
* a fall: the robot's torso tilts beyond 60 degrees (the run stops there);
* ball distance per phase: torso-to-ball distance along the ground, median over the cycles of
  each phase ``(t, left_active)``;
* holding: the 2023 rule's clock (ball within 0.12 m of the torso, reset after 0.5 s free);
  ``holding_fouls`` counts the referee's calls (play mode leaving PlayOn), ``max_held_s`` the
  longest the clock ran;
* a touch: a cycle in which the ball's ground speed rises by more than ``TOUCH_JUMP`` (only a
  contact speeds it up); ``touch_ball_speed_mps`` is the median (and ``_p90`` the 90th
  percentile) of the ball's speed after the touches: a toe meeting the ball fast sends it out
  of reach (``scripts/dribble/touches.py`` lists them with their phases).

``python -m benchmarks.dribble`` prints ``name: value`` lines for type 0 (``--types`` for more,
``--seeds 0 1 2 ...`` for several runs each: speeds then average over the runs that reached
the distance, counts add up). ``--set dfdl.controller.default.speed=0.8`` (repeatable) runs
the gaits with a setting of ``behaviors/data/dribble.yaml`` changed (a copy in a temporary
folder; the file itself is untouched), so that tuning trials are repo commands too;
``--jobs 2`` runs the seeds in parallel processes.

``--angles 90 180 -90`` starts each run with the direction to dribble at that angle (deg, +
= to the left) from the robot's first heading, the ball still 0.3 m ahead of it: the next
issue's episodes dribble at a random direction from -180 to 180 deg, so the gait must turn the
ball round. Those runs report per angle (``[angle=90]``) and add ``first_metre_s``: seconds
until the ball first lay 1 m along the new direction from its start (mean over the runs that
got there; ``first_metre_reached`` counts them).

``--trace 3`` prints, for every run, one ``run[...]`` line (how it ended, when, where) and,
for a run that fell or lost the ball, its last 3 s every 0.1 s (``trace[...]`` lines: phase,
ground-truth ball in the torso frame, the perceived ball, heading error, the command, torso tilt
and each foot's distance to the ball): falls must be explained before parameters change.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import tempfile
from collections import defaultdict, deque
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from behaviors.dribble import DRIBBLE_FILE
from learning.local_agent import LocalAgent
from sim.session import Session, SessionConfig
from world.nao_model import ROBOT_TYPES
from world.yaml_config import apply_overrides

#: Cycle length (s).
CYCLE = 0.02
#: A rise of the ball's ground speed (m/s) within one cycle that counts as a touch.
TOUCH_JUMP = 0.15
#: The robot starts this far behind the ball (m), as the kick-in-motion episodes do.
START_BEHIND = 0.3
#: The ball counts as lost beyond this distance from the torso (m): a dribble long kicks the
#: ball with the swinging toe to about 1 m/s, and a ball rolling at v goes v * 0.94 s further
#: (the server's rolling decay), so a ball the robot follows stays within about 1 m; beyond it
#: the dribble's rhythm is broken ...
LOST_DISTANCE = 1.0
#: ... and counts as back within reach below this one (hysteresis).
REGAINED_DISTANCE = 0.6
#: The 2023 holding rule's radius (m) and reset time (s).
HOLD_RADIUS = 0.12
HOLD_RESET_S = 0.5
BALL_Z = 0.042
#: A trace keeps one sample in this many cycles (0.1 s).
TRACE_EVERY = 5


@dataclass
class DribbleRun:
    """What one dribble did (ground truth)."""

    kind: str
    robot_type: int
    foot: str
    direction_deg: float
    #: the direction's angle from the robot's first heading (deg, + = left)
    start_angle_deg: float = 0.0
    seconds: float = 0.0
    #: seconds until the ball first lay 1 m along the direction from its start (None: never)
    first_metre_s: float | None = None
    distance: float = 0.0  # metres the ball travelled along the direction
    reached: bool = False
    fell: bool = False
    ball_losses: int = 0
    max_gap: float = 0.0  # the furthest the ball got from the torso (m)
    holding_fouls: int = 0
    max_held_s: float = 0.0
    #: (t, left_active) -> torso-ball distances (m)
    phase_distances: dict[tuple[int, bool], list[float]] = field(
        default_factory=lambda: defaultdict(list)
    )
    seed: int = 0
    #: the ball's ground speed (m/s) after each touch
    touch_speeds: list[float] = field(default_factory=list)
    #: the last ``trace_seconds`` of the run, one line per sample (empty unless asked for)
    trace: list[str] = field(default_factory=list)

    @property
    def speed(self) -> float:
        """Ball speed along the direction (m/s) over the run; 0 unless it reached the goal."""
        return self.distance / self.seconds if self.reached and self.seconds > 0 else 0.0


def start_dribble_episode(
    robot_type: int, direction_deg: float = 0.0, seed: int = 0
) -> tuple[Session, LocalAgent]:
    """A session with one robot standing ``START_BEHIND`` m behind the ball at the field
    centre, facing ``direction_deg``, in PlayOn: the kick-in-motion episode's start.

    A beam may not cross the centre line, so the robot is beamed to the centre (or as far
    back as the direction needs to keep it in its own half) and, once standing, the ball is
    placed ``START_BEHIND`` m ahead of its torso along ``direction_deg``."""
    session = Session(SessionConfig(seed=seed, beam_noise=False))
    h = math.radians(direction_deg)
    beam = (-START_BEHIND * max(math.cos(h), 0.0), -START_BEHIND * math.sin(h), direction_deg)
    agent = LocalAgent.join(session, "Local", 1, robot_type, beam=beam)
    agent.trainer("(playMode PlayOn)")
    agent.rise_to_stand()
    x, y, _ = agent.robot.torso_position()
    bx, by = x + START_BEHIND * math.cos(h), y + START_BEHIND * math.sin(h)
    agent.trainer(f"(ball (pos {bx:.4f} {by:.4f} {BALL_Z}) (vel 0 0 0))")
    agent.run("pose", "stand")  # trainer commands act on the next cycle
    return session, agent


def dribble_to_phase(
    agent: LocalAgent,
    kind: str,
    direction_deg: float,
    seconds: float,
    phase: tuple[int, bool],
    foot: str = "left",
) -> int:
    """Dribble for ``seconds``, then on until the dribble is at ``phase`` (t, left_active of
    the real robot): the hand-over point of the kick-in-motion episodes, any of the 16 phases.
    Returns the cycles run; stops early (returning them too) if the robot falls."""
    t, left_active = phase
    if not 0 <= t <= 7:
        raise ValueError(f"phase t must be 0..7, got {t}")
    skill = agent.behavior.skill("dribble")
    cycles = 0
    for _ in range(round(seconds / CYCLE)):
        agent.run("dribble", kind, direction_deg, foot)
        cycles += 1
        if agent.robot.has_fallen():
            return cycles
    while skill.phase != (t, left_active) and not agent.robot.has_fallen():
        agent.run("dribble", kind, direction_deg, foot)
        cycles += 1
    return cycles


class _Holding:
    """The holding rule's clock for one player (ground truth)."""

    def __init__(self) -> None:
        self.held = 0.0
        self.free = 0.0
        self.longest = 0.0

    def update(self, distance: float) -> None:
        if distance <= HOLD_RADIUS:
            self.held += CYCLE
            self.free = 0.0
            self.longest = max(self.longest, self.held)
        else:
            self.free += CYCLE
            if self.free >= HOLD_RESET_S - 1e-9:
                self.held = 0.0


def run_dribble(
    kind: str,
    robot_type: int = 0,
    distance: float = 10.0,
    foot: str = "left",
    direction_deg: float = 0.0,
    seed: int = 0,
    max_seconds: float | None = None,
    data_file: Path = DRIBBLE_FILE,
    start_angle_deg: float = 0.0,
    trace_seconds: float = 0.0,
) -> DribbleRun:
    """Dribble until the ball travelled ``distance`` m along ``direction_deg`` (or fell, or
    ``max_seconds``, by default the time at 0.2 m/s plus 2 s, plus 4 s per 90 deg of
    ``start_angle_deg``), with the gait settings of ``data_file``. The robot starts facing
    ``start_angle_deg`` to the right of the direction, the ball 0.3 m ahead of it. With
    ``trace_seconds`` the run keeps its last that many seconds as :attr:`DribbleRun.trace`."""
    session, agent = start_dribble_episode(robot_type, direction_deg - start_angle_deg, seed)
    result = DribbleRun(kind, robot_type, foot, direction_deg, start_angle_deg, seed=seed)
    recent: deque[str] = deque(maxlen=max(1, round(trace_seconds / (CYCLE * TRACE_EVERY))))
    skill = agent.behavior.skill("dribble")
    skill.data_file = data_file
    turn_allowance = 4.0 * abs(start_angle_deg) / 90.0
    limit = max_seconds if max_seconds is not None else distance / 0.2 + 2.0 + turn_allowance
    h = math.radians(direction_deg)
    ux, uy = math.cos(h), math.sin(h)
    holding = _Holding()
    lost = False
    start_x, start_y, _ = session.ball.position()
    ball_speed = 0.0
    try:
        for cycle in range(round(limit / CYCLE)):
            agent.run("dribble", kind, direction_deg, foot)
            result.seconds = (cycle + 1) * CYCLE
            vx, vy, _ = session.ball.velocity()
            if math.hypot(vx, vy) - ball_speed > TOUCH_JUMP:
                result.touch_speeds.append(math.hypot(vx, vy))
            ball_speed = math.hypot(vx, vy)
            bx, by, _ = session.ball.position()
            tx, ty, _ = agent.robot.torso_position()
            gap = math.hypot(bx - tx, by - ty)
            result.phase_distances[skill.phase].append(gap)
            result.max_gap = max(result.max_gap, gap)
            holding.update(gap)
            if session.referee.play_mode != "PlayOn":
                result.holding_fouls += 1
                agent.trainer("(playMode PlayOn)")
            yaw = math.radians(agent.robot.torso_yaw_deg())
            ahead = math.cos(yaw) * (bx - tx) + math.sin(yaw) * (by - ty)
            if not lost and (gap > LOST_DISTANCE or ahead < 0.0):
                lost = True
                result.ball_losses += 1
            elif lost and gap < REGAINED_DISTANCE and ahead > 0.0:
                lost = False
            result.distance = ux * (bx - start_x) + uy * (by - start_y)
            if result.first_metre_s is None and result.distance >= 1.0:
                result.first_metre_s = result.seconds
            if trace_seconds > 0.0 and cycle % TRACE_EVERY == 0:
                recent.append(_trace_line(result.seconds, agent, session))
            if agent.robot.has_fallen():
                result.fell = True
                break
            if result.distance >= distance:
                result.reached = True
                break
        if trace_seconds > 0.0:
            recent.append(_trace_line(result.seconds, agent, session))
    finally:
        session.close()
    result.max_held_s = holding.longest
    result.trace = list(recent)
    return result


def _trace_line(seconds: float, agent: LocalAgent, session: Session) -> str:
    """One trace sample: what the robot did and where the ball lay (ground truth next to what
    the skill perceived), so that a fall can be told apart: trodden on the ball, spun while
    turning, tipped while braking ..."""
    skill = agent.behavior.skill("dribble")
    bx, by, _ = session.ball.position()
    tx, ty, _ = agent.robot.torso_position()
    yaw = math.radians(agent.robot.torso_yaw_deg())
    c, s = math.cos(yaw), math.sin(yaw)
    ahead, side = c * (bx - tx) + s * (by - ty), -s * (bx - tx) + c * (by - ty)
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, float(agent.robot.torso_up()[2])))))
    feet = agent.robot.body_positions(["lfoot", "rfoot"])
    lf, rf = (math.hypot(feet[f][0] - bx, feet[f][1] - by) for f in ("lfoot", "rfoot"))
    seen = skill.last_inputs
    perceived = (
        "seen -"
        if seen is None
        else f"seen ({seen.ball_x:+.2f},{seen.ball_y:+.2f}) err {seen.heading_error_deg:+5.1f}"
    )
    vx, vy, turn = skill.last_command
    t, left = skill.phase
    return (
        f"{seconds:6.2f}s phase ({t},{'L' if left else 'R'}) ball ({ahead:+.2f},{side:+.2f}) "
        f"{perceived} cmd ({vx:+.2f},{vy:+.2f},{turn:+5.1f}) tilt {tilt:4.1f} "
        f"feet-ball L {lf:.2f} R {rf:.2f}"
    )


def run_lines(run: DribbleRun) -> list[str]:
    """A ``run[...]`` line per run (how it ended) and, when it fell or lost the ball, its
    trace."""
    ending = "fell" if run.fell else "reached" if run.reached else "timeout"
    key = f"{run.kind}][type{run.robot_type}][seed={run.seed}][angle={run.start_angle_deg:g}"
    lines = [
        f"run[{key}]: {ending} at {run.seconds:.2f}s, {run.distance:.2f} m, "
        f"{run.ball_losses} losses, max gap {run.max_gap:.2f} m"
    ]
    if run.fell or run.ball_losses:
        lines += [f"trace[{key}]: {sample}" for sample in run.trace]
    return lines


def report_lines(runs: list[DribbleRun]) -> list[str]:
    """The ``name: value`` lines of one or more runs of the same gait, robot type and foot
    (several seeds): speeds over the runs that reached the distance, counts summed, the
    ball's distance per phase as the median over every cycle of every run."""
    first = runs[0]
    key = f"{first.kind}_{first.foot}" if first.foot != "left" else first.kind
    t = f"type{first.robot_type}"
    if first.start_angle_deg:
        t += f"][angle={first.start_angle_deg:g}"
    reached = [r.speed for r in runs if r.reached]
    lines = [
        f"{key}_mps[{t}]: {statistics.mean(reached) if reached else 0.0:.3f}",
        f"{key}_mps_min[{t}]: {min(reached) if reached else 0.0:.3f}",
        f"{key}_reached[{t}]: {len(reached)}/{len(runs)}",
        f"{key}_distance_m[{t}]: {min(r.distance for r in runs):.2f}",
        f"{key}_ball_losses[{t}]: {sum(r.ball_losses for r in runs)}",
        f"{key}_max_ball_distance_m[{t}]: {max(r.max_gap for r in runs):.2f}",
        f"{key}_falls[{t}]: {sum(int(r.fell) for r in runs)}",
        f"{key}_holding_fouls[{t}]: {sum(r.holding_fouls for r in runs)}",
        f"{key}_max_held_s[{t}]: {max(r.max_held_s for r in runs):.2f}",
    ]
    touches = sorted(v for r in runs for v in r.touch_speeds)
    if touches:
        p90 = touches[min(len(touches) - 1, int(0.9 * len(touches)))]
        lines.append(f"{key}_touch_ball_speed_mps[{t}]: {statistics.median(touches):.2f}")
        lines.append(f"{key}_touch_ball_speed_mps_p90[{t}]: {p90:.2f}")
    if first.start_angle_deg:
        firsts = [r.first_metre_s for r in runs if r.first_metre_s is not None]
        mean_first = statistics.mean(firsts) if firsts else 0.0
        lines.append(f"{key}_first_metre_reached[{t}]: {len(firsts)}/{len(runs)}")
        lines.append(f"{key}_first_metre_s[{t}]: {mean_first:.2f}")
        lines.append(f"{key}_first_metre_s_max[{t}]: {max(firsts, default=0.0):.2f}")
        return lines  # the per-phase distances are a straight dribble's figure
    for (phase_t, left), distances in sorted(pooled_phase_distances(runs).items()):
        if phase_t < 0 or not distances:
            continue
        side = "left" if left else "right"
        median = statistics.median(distances)
        lines.append(f"{key}_ball_distance_m[{t}][t={phase_t},{side}]: {median:.3f}")
    return lines


def with_settings(overrides: list[str], folder: Path, source: Path = DRIBBLE_FILE) -> Path:
    """A copy of the gait settings ``source`` in ``folder`` with ``overrides`` applied: each
    ``dotted.key=value`` (value read as YAML) replaces or adds that key. Returns its path."""
    data: dict[str, Any] = yaml.safe_load(source.read_text()) or {}
    apply_overrides(data, overrides, str(source))
    path = folder / source.name
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return path


def _run_one(
    arguments: tuple[str, int, float, str, float, int, Path, float, float],
) -> DribbleRun:
    kind, robot_type, distance, foot, direction, seed, data_file, angle, trace = arguments
    return run_dribble(
        kind,
        robot_type,
        distance,
        foot,
        direction,
        seed,
        data_file=data_file,
        start_angle_deg=angle,
        trace_seconds=trace,
    )


def pooled_phase_distances(runs: list[DribbleRun]) -> dict[tuple[int, bool], list[float]]:
    """The ball's distance at every cycle of every run, by phase (before the first step: t -1)."""
    pooled: dict[tuple[int, bool], list[float]] = defaultdict(list)
    for run in runs:
        for phase, distances in run.phase_distances.items():
            pooled[phase].extend(distances)
    return dict(pooled)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--types", type=int, nargs="+", default=[0], choices=ROBOT_TYPES)
    parser.add_argument("--kinds", nargs="+", default=["dfdl", "lfdl"])
    parser.add_argument("--foot", default="left", choices=("left", "right"))
    parser.add_argument("--distance", type=float, default=10.0)
    parser.add_argument("--direction", type=float, default=0.0)
    parser.add_argument("--seeds", type=int, nargs="+", default=[0])
    parser.add_argument(
        "--angles", type=float, nargs="+", default=[0.0], help="start angles (deg, + = left)"
    )
    parser.add_argument("--set", action="append", default=[], metavar="DOTTED.KEY=VALUE")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument(
        "--trace", type=float, default=0.0, metavar="SECONDS", help="per-run lines and traces"
    )
    parser.add_argument(
        "--plot",
        type=Path,
        metavar="PNG",
        help="box plots of the ball's distance per phase (straight runs; needs matplotlib)",
    )
    args = parser.parse_args(argv)
    per_phase: dict[str, dict[tuple[int, bool], list[float]]] = {}
    with tempfile.TemporaryDirectory() as folder:
        data_file = with_settings(args.set, Path(folder)) if args.set else DRIBBLE_FILE
        with ProcessPoolExecutor(max(args.jobs, 1)) as pool:
            for robot_type in args.types:
                for kind in args.kinds:
                    for angle in args.angles:
                        common = (args.distance, args.foot, args.direction)
                        jobs = [
                            (kind, robot_type, *common, s, data_file, angle, args.trace)
                            for s in args.seeds
                        ]
                        runs = list(pool.map(_run_one, jobs))
                        if args.trace > 0.0:
                            for line in (line for run in runs for line in run_lines(run)):
                                print(line, flush=True)
                        for line in report_lines(runs):
                            print(line, flush=True)
                        if not angle:
                            label = f"{kind.upper()}, type {robot_type}, {args.foot} foot"
                            per_phase[label] = pooled_phase_distances(runs)
    if args.plot is not None and per_phase:
        from benchmarks.plots import phase_distance_plot

        seeds = " ".join(str(s) for s in args.seeds)
        title = f"torso-to-ball distance per phase, {args.distance:g} m runs, seeds {seeds}"
        print(f"plot: {phase_distance_plot(per_phase, args.plot, title)}", flush=True)


if __name__ == "__main__":
    main()
