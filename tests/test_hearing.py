"""The real server's hearing rules (sim.hearing): capacity per team, first speaker wins, the
speaker hears itself, directions in the listener's team frame, 50 m range."""

from __future__ import annotations

import math

import pytest

from sim.hearing import Ear, Listener, broadcast


def _listener(team="Us", side="left", x=0.0, y=0.0) -> Listener:
    return Listener(Ear(), team, side, x, y)


def _cycle(speakers, listeners):
    """One cycle: the messages said, then every listener's perception (own team 'Us')."""
    broadcast(speakers, listeners)
    return [[h.message for h in ear.ear.take(ear.team, 1.0)] for ear in listeners]


def test_the_first_teammate_is_heard_and_then_the_team_is_silent_for_a_cycle():
    a, b, me = _listener(x=1.0), _listener(x=2.0), _listener()
    everyone = [a, b, me]
    heard = _cycle([(a, "a1"), (b, "b1")], everyone)
    assert heard[2] == ["a1"]  # b1 came second in the same cycle: lost
    assert heard[0] == ["a1", "b1"]  # a heard itself, then b (its capacity was full)
    assert _cycle([(b, "b2")], everyone)[2] == []  # capacity 1 of 2: deaf to the team
    assert _cycle([(b, "b3")], everyone)[2] == ["b3"]  # recovered


def test_opponents_have_their_own_capacity():
    mate, them, me = _listener(x=1.0), _listener("Them", "right", x=3.0), _listener()
    broadcast([(mate, "m"), (them, "t")], [mate, them, me])
    heard = me.ear.take("Us", 2.5)
    assert [(h.team, h.message) for h in heard] == [("Us", "m"), ("Them", "t")]
    assert all(h.time == 2.5 for h in heard)


def test_the_speaker_hears_itself_whatever_its_capacity():
    me, other = _listener(), _listener(x=1.0)
    for k in range(3):
        heard = _cycle([(other, f"o{k}"), (me, f"s{k}")], [other, me])
        assert heard[1][0] == f"s{k}"


def test_direction_is_in_the_listeners_team_frame():
    speaker = _listener(x=1.0, y=1.0)
    left = _listener()
    right = _listener("Them", "right")
    broadcast([(speaker, "x")], [speaker, left, right])
    (to_left,) = [h for h in left.ear.take("Us", 0.0) if h.direction != "self"]
    (to_right,) = right.ear.take("Them", 0.0)
    assert to_left.direction == pytest.approx(45.0)
    assert to_right.direction == pytest.approx(-135.0)  # the right team's view is turned 180


def test_messages_travel_50_m():
    speaker, near, far = _listener(), _listener(x=49.0), _listener(x=math.hypot(40.0, 31.0))
    assert _cycle([(speaker, "x")], [speaker, near, far])[1:] == [["x"], []]
