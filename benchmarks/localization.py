"""World model benchmark: localisation and ball tracking against the stand-in server's ground
truth, and the cost of ``WorldModel.update``.

Run: ``.venv/bin/python benchmarks/localization.py [--cycles N]``. Prints ``name: value`` lines:

* ``loc_error_m_median`` / ``loc_error_m_p90`` / ``loc_error_deg_median`` - pose error while the
  trainer carries a standing robot along a winding path (6 cm and 2 deg every 5 cycles, a
  brisk walk), once for each team, every cycle after the first fix. The trainer's turns
  reach no gyro, so the heading lags by up to 2 deg until the next image (see the p90);
* ``loc_restarts`` - how often the filter restarted from landmarks (the path turns the robot
  round on the spot, a 180 deg jump, where it meets the field's edge);
* ``world_update_us_median`` / ``world_update_us_p99`` - ``WorldModel.update`` per cycle
  (perceptions parsed beforehand; two cycles in three carry no image);
* ``world_update_with_fk_us_median`` - the same when a behaviour also reads this cycle's
  ``body_transforms`` (the kinematics is computed on demand);
* ``parse_us_median`` - ``parse_perception`` of the same messages, for scale;
* ``loc_walking_error_m_median`` / ``loc_walking_error_deg_median`` / ``loc_walking_falls`` -
  pose error while a type-0 agent walks with its own walk skill (odometry from the walk, images
  every third cycle), every cycle after the first fix while it is up;
* ``ball_error_m_median`` / ``ball_velocity_error_mps_median`` - the ball filter against the
  true ball while balls roll past a standing robot at 1-4 m/s (cycles where the ball was seen
  within the last 0.1 s);
* ``ball_stop_error_m_median`` - ``predicted_stop()`` half a second after each launch against
  where the ball came to rest.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sim.monitor import parse_trainer_commands
from sim.session import Session, SessionConfig
from world.localization import wrap_deg
from world.perception import parse_perception
from world.world_model import WorldModel

STANDING_Z = 0.38


def _trainer(session: Session, text: str) -> None:
    commands, errors = parse_trainer_commands(text.encode())
    if errors:
        raise ValueError(errors)
    session.trainer_command(commands)


def _connect(session: Session, team: str, unum: int = 1) -> int:
    return session.join(team, unum)


def _move(session: Session, side: str, x: float, y: float, heading: float) -> None:
    """Stand the robot at world (x, y) facing ``heading`` (deg, 0 = world +x)."""
    _trainer(session, f"(agent (unum 1) (team {side}) (move {x} {y} {STANDING_Z} {heading - 90}))")


def carried_robot(side: str, cycles: int, seed: int) -> dict[str, list[float]]:
    """Carry one robot along a winding path; pose errors, timings and raw messages."""
    session = Session(SessionConfig(seed=seed))
    rng = np.random.default_rng(seed)
    out: dict[str, list] = {"m": [], "deg": [], "update": [], "messages": []}
    try:
        if side == "Right":
            _connect(session, "Others")
        agent = _connect(session, "Mine")
        model = WorldModel(0, "Mine")
        # PlayOn: before kick-off the referee (as rcssserver3d's) moves robots out of the
        # opponent half and the centre circle, which would fight the trainer's path
        _trainer(session, "(playMode PlayOn)")
        x, y = rng.uniform(-10.0, 10.0), rng.uniform(-6.0, 6.0)
        heading, turn = rng.uniform(-180.0, 180.0), 2.0
        for cycle in range(cycles):
            if cycle % 5 == 0 and cycle > 3:
                if cycle % 400 == 0:
                    turn = -turn  # wind the other way now and then
                h = math.radians(heading)
                x, y = x + 0.06 * math.cos(h), y + 0.06 * math.sin(h)
                if abs(x) > 13.5 or abs(y) > 9.0:
                    heading += 180.0
                heading += turn
                _move(session, side, x, y, heading)
            session.step()
            message = session.perception(agent)
            perception = parse_perception(message)
            start = time.perf_counter()
            model.update(perception)
            out["update"].append(time.perf_counter() - start)
            out["messages"].append(message)
            gx, gy, gh = session.agents[agent].robot.team_frame_pose(side)
            pose = model.pose
            if cycle >= 30 and pose is not None:
                out["m"].append(math.hypot(pose.x - gx, pose.y - gy))
                out["deg"].append(abs(wrap_deg(pose.heading_deg - gh)))
        out["restarts"] = [model.localizer.restarts]
        return out
    finally:
        session.close()


def rolling_balls(launches: int, seed: int) -> dict[str, list[float]]:
    """Roll balls past a standing robot; ball position/velocity errors and stop errors."""
    session = Session(SessionConfig(seed=seed))
    rng = np.random.default_rng(seed)
    out: dict[str, list[float]] = {"m": [], "mps": [], "stop": []}
    try:
        agent = _connect(session, "Mine")
        model = WorldModel(0, "Mine")

        def step() -> None:
            session.step()
            model.update(parse_perception(session.perception(agent)))

        for _ in range(3):
            step()
        _move(session, "Left", -4.0, 0.0, 0.0)
        _trainer(session, "(playMode PlayOn)")
        for _ in range(40):
            step()
        for _ in range(launches):
            bx, by = rng.uniform(-3.0, -1.0), rng.uniform(-1.5, 1.5)
            speed, angle = rng.uniform(1.0, 4.0), rng.uniform(-180.0, 180.0)
            vx, vy = speed * math.cos(math.radians(angle)), speed * math.sin(math.radians(angle))
            _trainer(session, f"(ball (pos {bx} {by} 0.042) (vel {vx} {vy} 0))")
            stop_guess = None
            for cycle in range(300):
                step()
                if cycle < 8 or model.ball.time_since_seen > 0.1:
                    continue
                true_p, true_v = session.ball.position(), session.ball.velocity()
                px, py = model.ball.position
                ex, ey = model.ball.velocity
                out["m"].append(math.hypot(px - true_p[0], py - true_p[1]))
                out["mps"].append(math.hypot(ex - true_v[0], ey - true_v[1]))
                if cycle == 25:
                    stop_guess = model.ball.predicted_stop()
            if stop_guess is not None:
                rest = session.ball.position()
                out["stop"].append(math.hypot(stop_guess[0] - rest[0], stop_guess[1] - rest[1]))
        return out
    finally:
        session.close()


def update_costs(messages: list[bytes]) -> dict[str, float]:
    """Time update (alone and with a kinematics read) and parsing on recorded messages."""
    parsed = [parse_perception(m) for m in messages]
    timings: dict[str, list[float]] = {"update": [], "with_fk": [], "parse": []}
    for key in ("update", "with_fk"):
        model = WorldModel(0, "Mine")
        for perception in parsed:
            start = time.perf_counter()
            model.update(perception)
            if key == "with_fk":
                _ = model.body_transforms
            timings[key].append(time.perf_counter() - start)
    for message in messages:
        start = time.perf_counter()
        parse_perception(message)
        timings["parse"].append(time.perf_counter() - start)
    return {
        "world_update_us_median": float(np.median(timings["update"]) * 1e6),
        "world_update_us_p99": float(np.percentile(timings["update"], 99) * 1e6),
        "world_update_with_fk_us_median": float(np.median(timings["with_fk"]) * 1e6),
        "parse_us_median": float(np.median(timings["parse"]) * 1e6),
    }


class _WalkAround:
    """A strategy for one agent: beam in, then walk with a slowly changing command."""

    def __init__(self, speed: float) -> None:
        self.speed = speed
        self.cycle = 0

    def decide(self, world, behavior):
        from agent.strategy import Decision

        self.cycle += 1
        if self.cycle == 2:
            return Decision(beam=(-6.0, -2.0, 0.0))
        if self.cycle < 60 or world.robot.is_fallen:
            behavior.execute("pose", "stand")
            return Decision()
        turn = 20.0 * math.sin(self.cycle / 150.0)
        behavior.execute("walk_velocity", self.speed, 0.0, turn)
        return Decision()


def walking_robot(seconds: float, seed: int, speed: float = 0.3) -> dict[str, list[float]]:
    """Pose error of a type-0 agent walking (its own walk, its own odometry), every cycle
    after the first fix while it stands; and how often it fell."""
    from agent.agent import Agent, AgentConfig
    from sim.server import SoccerServer

    session = Session(SessionConfig(seed=seed))
    server = SoccerServer(session, "127.0.0.1", 0, 0, sync=True)
    agent = Agent(AgentConfig("Walker", 1, 0), _WalkAround(speed))
    agent_id = server.add_local_agent(agent)
    errors: dict[str, list[float]] = {"m": [], "deg": [], "falls": [0]}
    was_fallen = False
    try:
        for _ in range(int(seconds / 0.02)):
            server.run_cycle()
            robot = session.agents[agent_id].robot
            fallen = robot.has_fallen()
            errors["falls"][0] += fallen and not was_fallen
            was_fallen = fallen
            pose = agent.world.pose
            if pose is None or fallen or agent.strategy.cycle < 60:
                continue
            x, y, _ = robot.torso_position()
            errors["m"].append(math.hypot(pose.x - x, pose.y - y))
            errors["deg"].append(abs(wrap_deg(pose.heading_deg - robot.torso_yaw_deg())))
    finally:
        server.close()
        session.close()
    return errors


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cycles", type=int, default=1500, help="cycles per team's path")
    parser.add_argument("--launches", type=int, default=8, help="balls rolled")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--walk-seconds", type=float, default=30.0, help="walking measurement")
    args = parser.parse_args()

    left = carried_robot("Left", args.cycles, args.seed)
    right = carried_robot("Right", args.cycles, args.seed + 1)
    metres = left["m"] + right["m"]
    degrees = left["deg"] + right["deg"]
    print(f"loc_error_m_median: {np.median(metres):.4f}")
    print(f"loc_error_m_p90: {np.percentile(metres, 90):.4f}")
    print(f"loc_error_deg_median: {np.median(degrees):.3f}")
    print(f"loc_error_deg_p90: {np.percentile(degrees, 90):.3f}")
    print(f"loc_restarts: {left['restarts'][0] + right['restarts'][0]}")
    for name, value in update_costs(left["messages"]).items():
        print(f"{name}: {value:.1f}")
    walking = walking_robot(args.walk_seconds, args.seed)
    if walking["m"]:
        print(f"loc_walking_error_m_median: {np.median(walking['m']):.4f}")
        print(f"loc_walking_error_deg_median: {np.median(walking['deg']):.3f}")
    print(f"loc_walking_falls: {walking['falls'][0]}")
    balls = rolling_balls(args.launches, args.seed)
    print(f"ball_error_m_median: {np.median(balls['m']):.4f}")
    print(f"ball_velocity_error_mps_median: {np.median(balls['mps']):.3f}")
    print(f"ball_stop_error_m_median: {np.median(balls['stop']):.3f}")


if __name__ == "__main__":
    main()
