"""Self-localisation: the filter on exact synthetic views, and the whole world model against the
stand-in server's ground truth while the trainer carries the robot along a path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim.monitor import parse_trainer_commands
from sim.session import Session, SessionConfig
from world.localization import Localizer, team_landmarks, team_lines, wrap_deg
from world.perception import parse_perception
from world.world_model import WorldModel

#: the server's standing torso height (m), where the trainer puts the robot
STANDING_Z = 0.38


# ------------------------------------------------------------------------------ synthetic views
def _ego(pose: tuple[float, float, float], point: tuple[float, ...]) -> tuple[float, float]:
    """Where a team-frame point appears in the ego frame (forward, left) of ``pose``."""
    x, y, heading = pose
    h = math.radians(heading)
    dx, dy = point[0] - x, point[1] - y
    return (math.cos(h) * dx + math.sin(h) * dy, -math.sin(h) * dx + math.cos(h) * dy)


def _view(pose, side=None, names=None):
    marks = team_landmarks(side)
    names = names if names is not None else list(marks)
    return {name: _ego(pose, marks[name]) for name in names}


def _line_view(pose, side=None, indices=(0,), fractions=(0.3, 0.6)):
    """Pieces of the given field lines (team frame of ``side``) as seen from ``pose``."""
    lines = team_lines(side)
    pieces = []
    for i in indices:
        a, b = lines[i]
        ends = [a + f * (b - a) for f in fractions]
        pieces.append([_ego(pose, e) for e in ends])
    return np.array(pieces)


def test_two_exact_landmarks_give_the_exact_pose():
    loc = Localizer()
    truth = (-4.0, 2.5, 30.0)
    assert loc.update(_view(truth, names=["G1R", "F2R"]))
    pose = loc.pose
    assert (pose.x, pose.y) == pytest.approx(truth[:2], abs=1e-3)
    assert wrap_deg(pose.heading_deg - truth[2]) == pytest.approx(0.0, abs=0.05)
    assert 0.0 < pose.confidence <= 1.0


def test_one_landmark_alone_cannot_start():
    loc = Localizer()
    assert not loc.update(_view((0.0, 0.0, 0.0), names=["G1R"]))
    assert loc.pose is None


def test_right_team_frame_is_mirrored():
    """The same world view gives the mirrored pose (heading + 180) for the right team."""
    world_pose = (5.0, -3.0, 150.0)
    view = _view(world_pose)  # left team frame = world frame
    right = Localizer(side="right")
    right.update(view)
    pose = right.pose
    assert (pose.x, pose.y) == pytest.approx((-5.0, 3.0), abs=1e-3)
    assert wrap_deg(pose.heading_deg - (150.0 + 180.0)) == pytest.approx(0.0, abs=0.05)


def test_switching_side_mirrors_a_known_pose():
    loc = Localizer()
    loc.set_pose(2.0, 1.0, 10.0)
    loc.set_side("right")
    pose = loc.pose
    assert (pose.x, pose.y, wrap_deg(pose.heading_deg)) == pytest.approx((-2.0, -1.0, -170.0))


def test_odometry_moves_along_the_heading_and_grows_uncertainty():
    loc = Localizer(use_gyro_heading=False)
    loc.set_pose(0.0, 0.0, 90.0, sigma_m=0.01, sigma_deg=0.5)
    before = loc.pose.sigma_xy
    for _ in range(10):
        loc.add_odometry(0.1, 0.0, 0.0)
    pose = loc.pose
    assert (pose.x, pose.y) == pytest.approx((0.0, 1.0), abs=1e-9)
    assert pose.sigma_xy > before
    loc.add_odometry(0.0, 0.0, 45.0)
    assert loc.pose.heading_deg == pytest.approx(135.0)


def test_gyro_heading_ignores_the_odometry_turn():
    loc = Localizer()
    loc.set_pose(0.0, 0.0, 0.0)
    loc.predict(90.0, 0.5)  # 90 deg/s for half a second
    loc.add_odometry(0.0, 0.0, 45.0)  # the same turn as the walk engine saw it
    assert loc.pose.heading_deg == pytest.approx(45.0)


def test_lines_correct_a_pose_that_one_landmark_cannot():
    """Near the side line, one flag and two lines: the position error across the lines
    shrinks, which the flag alone (with an uncertain prior) could not do."""
    truth = (3.0, 8.0, 80.0)
    loc = Localizer()
    loc.set_pose(truth[0] + 0.25, truth[1] - 0.25, truth[2] + 2.0, sigma_m=0.4, sigma_deg=4.0)
    lines = _line_view(truth, indices=(3, 0))  # the left side line and the centre line
    assert loc.update(_view(truth, names=["F1R"]), lines)
    pose = loc.pose
    assert math.hypot(pose.x - truth[0], pose.y - truth[1]) < 0.05
    assert abs(wrap_deg(pose.heading_deg - truth[2])) < 0.5


def test_a_carried_robot_restarts_from_the_landmarks():
    loc = Localizer()
    loc.update(_view((-5.0, 0.0, 0.0)))
    far = (4.0, -6.0, -120.0)
    assert loc.update(_view(far, names=["F2L", "G2L", "G1L"]))
    pose = loc.pose
    assert loc.restarts == 1
    assert math.hypot(pose.x - far[0], pose.y - far[1]) < 1e-3


def test_one_disagreeing_landmark_widens_instead_of_jumping():
    loc = Localizer()
    loc.update(_view((-5.0, 0.0, 0.0)))
    before = loc.pose
    assert not loc.update(_view((5.0, 5.0, 90.0), names=["F1L"]))
    after = loc.pose
    assert (after.x, after.y) == (before.x, before.y)
    assert after.sigma_xy > before.sigma_xy


# ------------------------------------------------------------------------------ against the server
def _trainer(session: Session, text: str) -> None:
    commands, errors = parse_trainer_commands(text.encode())
    assert not errors, errors
    session.trainer_command(commands)


def _connect(session: Session, team: str, unum: int = 1) -> int:
    return session.join(team, unum)


def _path(cycles: int, start: tuple[float, float, float], every: int):
    """Trainer moves: walk forward 6 cm and turn 2 deg every ``every`` cycles (a brisk walk
    on a wide curve), reflecting off the field's edges."""
    x, y, heading = start
    for cycle in range(cycles):
        if cycle % every == 0:
            h = math.radians(heading)
            x, y = x + 0.06 * math.cos(h), y + 0.06 * math.sin(h)
            if abs(x) > 13.5 or abs(y) > 9.0:
                heading += 180.0
            heading += 2.0
            yield cycle, (x, y, heading)
        else:
            yield cycle, None


def _errors(side: str, start, cycles: int = 600, seed: int = 5):
    """Localisation errors (m, deg) per cycle while the trainer carries one robot around."""
    session = Session(SessionConfig(seed=seed))
    try:
        if side == "Right":
            _connect(session, "Others")  # the first team to connect plays on the left
        agent = _connect(session, "Mine")
        model = WorldModel(0, "Mine")
        distances, angles = [], []
        for cycle, move in _path(cycles, start, every=5):
            if move is not None:
                x, y, heading = move  # world frame; the trainer's angle 0 faces world +y
                _trainer(
                    session,
                    f"(agent (unum 1) (team {side}) (move {x} {y} {STANDING_Z} {heading - 90}))",
                )
            session.step()
            model.update(parse_perception(session.perception(agent)))
            gx, gy, gh = session.agents[agent].robot.team_frame_pose(side)
            pose = model.pose
            if cycle >= 30 and pose is not None:
                distances.append(math.hypot(pose.x - gx, pose.y - gy))
                angles.append(abs(wrap_deg(pose.heading_deg - gh)))
        assert model.side == side.lower()
        return np.array(distances), np.array(angles)
    finally:
        session.close()


@pytest.mark.parametrize(
    ("side", "start"),
    [("Left", (-6.0, -2.0, 20.0)), ("Right", (4.0, 3.0, 200.0))],
)
def test_pose_follows_a_carried_robot(side, start):
    distances, angles = _errors(side, start)
    assert len(distances) > 500, "the robot localised itself from its first images"
    assert np.median(distances) <= 0.1
    assert np.median(angles) <= 5.0
    assert np.percentile(distances, 95) < 0.3
