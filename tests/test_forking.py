"""The fork helper the get-up screens play their variants with (scripts/get_up/forking.py)."""

import os

import pytest

from scripts.get_up.forking import ForkedTaskError, forked_call, forked_map

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="needs os.fork")


def test_results_come_back_in_task_order_with_several_children_at_once():
    tasks = [lambda i=i: (i, os.getpid()) for i in range(7)]
    results = forked_map(tasks, jobs=3)
    assert [i for i, _ in results] == list(range(7))
    assert all(pid != os.getpid() for _, pid in results)


def test_a_result_larger_than_a_pipe_buffer_comes_back_whole():
    big = bytes(range(256)) * 4096  # 1 MiB, far above Linux's 64 KiB pipe buffer
    assert forked_map([lambda: big, lambda: big[::-1]], jobs=2) == [big, big[::-1]]


def test_the_child_changes_nothing_in_the_parent():
    state = {"value": 1}

    def change() -> int:
        state["value"] = 2
        return state["value"]

    assert forked_call(change) == 2
    assert state == {"value": 1}


def test_a_task_that_raises_names_itself_and_its_error():
    def fail() -> None:
        raise ValueError("no such frame")

    with pytest.raises(ForkedTaskError, match=r"task 1 raised:(.|\n)*ValueError: no such frame"):
        forked_map([lambda: 1, fail, lambda: 3], jobs=2)


def test_jobs_must_be_positive():
    with pytest.raises(ValueError, match="jobs"):
        forked_map([lambda: 1], jobs=0)
