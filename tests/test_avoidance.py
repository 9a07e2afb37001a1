"""Walking round robots on the way to a target (agent/avoidance.py)."""

from __future__ import annotations

import math

import pytest

from agent.avoidance import avoidance_waypoint


def _waypoint(robots, clear_m=0.8, target_zone_m=0.6, beyond_m=0.3):
    return avoidance_waypoint((0.0, 0.0), (5.0, 0.0), robots, clear_m, target_zone_m, beyond_m)


def test_a_clear_way_needs_no_waypoint():
    assert _waypoint([]) is None
    assert _waypoint([(2.0, 1.5)]) is None  # beside the way, farther than clear_m
    assert _waypoint([(-1.0, 0.0)]) is None  # behind
    assert _waypoint([(6.0, 0.0)]) is None  # beyond the target
    assert _waypoint([(4.7, 0.1)]) is None  # at the target: a contest, not an obstacle
    assert _waypoint([(2.0, 0.0)], clear_m=0.0) is None  # off


def test_the_waypoint_passes_the_robot_on_the_side_away_from_it():
    left = _waypoint([(2.0, 0.2)])
    assert left == pytest.approx((2.3, -0.6))
    right = _waypoint([(2.0, -0.2)])
    assert right == pytest.approx((2.3, 0.6))


def test_the_nearest_robot_in_the_way_is_passed_first():
    assert _waypoint([(3.5, 0.1), (1.5, -0.1)]) == pytest.approx((1.8, 0.7))


def test_walking_to_the_waypoint_leaves_the_robot_behind_before_reaching_it():
    robot = (2.0, 0.2)
    waypoint = _waypoint([robot])
    assert waypoint is not None
    # from close to the waypoint the robot is behind the walker: the way to the target is clear
    near = (waypoint[0] - 0.05, waypoint[1])
    assert avoidance_waypoint(near, (5.0, 0.0), [robot], 0.8, 0.6, 0.3) is None
    # and on the way there the side does not flip
    halfway = (waypoint[0] / 2, waypoint[1] / 2)
    again = avoidance_waypoint(halfway, (5.0, 0.0), [robot], 0.8, 0.6, 0.3)
    assert again is None or again[1] < 0.0
    assert math.dist(robot, waypoint) > 0.8
