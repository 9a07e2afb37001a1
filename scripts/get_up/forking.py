"""Play many variants from one fallen robot: each play runs in a forked child of the process
that holds the simulator, so the parent's world stays exactly as it was and every variant
starts from the same fall (common random numbers, outcomes equal to the benchmark's).

Why a module: the screen (``screen_sequences.py``, one child at a time) and the evolution
strategy (``es_search.py``, ``--jobs`` children at once) need the same fork, pipe and reap
code, and the details matter: the parent must read a child's pipe before waiting for it (a
result larger than the pipe's buffer would otherwise block both), and a child that raises
must say why instead of leaving an empty pipe behind. POSIX only (``os.fork``).
"""

from __future__ import annotations

import os
import pickle
import selectors
import traceback
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any


class ForkedTaskError(RuntimeError):
    """A task raised in its forked child; the message carries the child's traceback."""


@dataclass
class _Running:
    index: int
    pid: int
    chunks: list[bytes] = field(default_factory=list)


def forked_map(tasks: Iterable[Callable[[], Any]], jobs: int = 1) -> list[Any]:
    """Run each task in a forked child, at most ``jobs`` at once, and return their results in
    the order of ``tasks``. A task's result must pickle; a task that raises makes this raise
    :class:`ForkedTaskError` (after every started child has been reaped)."""
    if jobs < 1:
        raise ValueError(f"jobs must be at least 1, got {jobs}")
    results: dict[int, Any] = {}
    failures: list[str] = []
    selector = selectors.DefaultSelector()
    running = 0
    for index, task in enumerate(tasks):
        while running >= jobs:
            running -= _collect_one(selector, results, failures)
        read, pid = _start(task)
        selector.register(read, selectors.EVENT_READ, _Running(index, pid))
        running += 1
    while running:
        running -= _collect_one(selector, results, failures)
    selector.close()
    if failures:
        raise ForkedTaskError("\n".join(failures))
    return [results[i] for i in range(len(results))]


def forked_call(task: Callable[[], Any]) -> Any:
    """``task()`` run in a forked child (the caller's process state is left untouched)."""
    return forked_map([task])[0]


def _start(task: Callable[[], Any]) -> tuple[int, int]:
    """Fork a child that runs ``task`` and writes ``(ok, payload)`` pickled to a pipe; returns
    the pipe's read end and the child's pid."""
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # child: run, report, exit without the parent's cleanup handlers
        os.close(read)
        try:
            try:
                message = pickle.dumps((True, task()))
            except BaseException:  # every failure goes back to the parent
                message = pickle.dumps((False, traceback.format_exc()))
            with os.fdopen(write, "wb") as pipe:
                pipe.write(message)
        finally:
            os._exit(0)
    os.close(write)
    return read, pid


def _collect_one(
    selector: selectors.BaseSelector, results: dict[int, Any], failures: list[str]
) -> int:
    """Read from the running children's pipes until one has closed its pipe; reap that child
    and store its result. Returns the number of children finished (0 or 1)."""
    for key, _ in selector.select():
        child: _Running = key.data
        chunk = os.read(key.fd, 1 << 16)
        if chunk:
            child.chunks.append(chunk)
            continue
        selector.unregister(key.fd)
        os.close(key.fd)
        os.waitpid(child.pid, 0)
        data = b"".join(child.chunks)
        if not data:
            failures.append(f"task {child.index}: the child exited without a result")
            results[child.index] = None
            return 1
        ok, payload = pickle.loads(data)
        if not ok:
            failures.append(f"task {child.index} raised:\n{payload}")
        results[child.index] = payload if ok else None
        return 1
    return 0
