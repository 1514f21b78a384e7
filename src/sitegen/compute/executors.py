"""Where tabulation work runs: here (serial), in local processes, or on a Dask cluster.

All three are `concurrent.futures.Executor`s; the build submits work units and collects their
results in plan order, so the output is the same byte for byte whichever runs it.
"""
from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from contextlib import contextmanager
from typing import Iterable, Iterator


class SerialExecutor(Executor):
    """Runs each task at once, in this process."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        """Run `fn` now and return its finished future."""
        future: Future = Future()
        try:
            future.set_result(fn(*args, **kwargs))
        except BaseException as error:  # handed to whoever reads the result, as a pool would
            future.set_exception(error)
        return future


def _pin_blas_threads() -> None:
    # Small linear algebra is ~10x faster single-threaded, and workers must not oversubscribe cores.
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    os.environ["OMP_NUM_THREADS"] = "1"


@contextmanager
def executor_for(jobs: int = 1, scheduler: str | None = None) -> Iterator[Executor]:
    """A serial executor, a pool of `jobs` local processes, or a Dask cluster's executor; closed after."""
    if scheduler:
        try:
            from distributed import Client
        except ImportError:
            raise RuntimeError("--scheduler needs Dask: pip install -e '.[dask]'") from None
        with Client(scheduler) as client:
            client.run(_pin_blas_threads)
            yield client.get_executor()
    elif jobs > 1:
        with ProcessPoolExecutor(max_workers=jobs, initializer=_pin_blas_threads) as pool:
            yield pool
    else:
        yield SerialExecutor()


def results_in_order(executor: Executor, function, units: Iterable) -> Iterator:
    """`function(unit)` for each unit, in order. A pool is given every unit at once; the serial
    executor runs each only when its result is asked for, so that a caller sees the work advance."""
    if isinstance(executor, SerialExecutor):
        return (function(unit) for unit in units)
    futures = [executor.submit(function, unit) for unit in units]
    return (future.result() for future in futures)


class Background:
    """One call running in a process of its own while this one goes on; `result()` waits for it.

    The process is spawned, not forked (a fork would copy the locks of this process's threads), and
    is a daemon: a build that stops early does not wait for it.
    """

    def __init__(self, function, *args):
        context = multiprocessing.get_context("spawn")
        self._answer, answer = context.Pipe(duplex=False)
        self._process = context.Process(target=_answer_with, args=(answer, function, args), daemon=True)
        self._process.start()
        answer.close()

    def result(self):
        """What the call returned; raises BackgroundFailed if it raised or its process ended without answering."""
        try:
            done, value = self._answer.recv()
        except EOFError:
            done, value = False, f"its process ended with code {self._process.exitcode}"
        self._process.join()
        if not done:
            raise BackgroundFailed(value)
        return value

    def stop(self) -> None:
        """End the call if it still runs (its result is no longer wanted)."""
        if self._process.is_alive():
            self._process.terminate()
        self._process.join()


class BackgroundFailed(Exception):
    """A call in the background raised (its type and message) or its process died."""


def _answer_with(answer, function, args) -> None:
    try:
        value = (True, function(*args))
    except BaseException as error:  # reported to the waiting process, which decides what to do
        value = (False, f"{type(error).__name__}: {error}")
    answer.send(value)
    answer.close()
