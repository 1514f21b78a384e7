"""Where tabulation work runs: here (serial), in local processes, or on a Dask cluster.

All three are `concurrent.futures.Executor`s; the build submits work units and collects their
results in plan order, so the output is the same byte for byte whichever runs it.
"""

from __future__ import annotations

import ctypes
import multiprocessing
import os
import pickle
import select
import signal
import subprocess
import sys
import threading
from collections.abc import Iterable, Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager

_PR_SET_PDEATHSIG = 1  # prctl's option: the signal a process gets when its parent ends (linux/prctl.h)


def _load_prctl():
    """The C library's prctl (Linux), looked up once here: a forked child should not have to load anything."""
    try:
        return getattr(ctypes.CDLL(None, use_errno=True), "prctl", None)
    except (OSError, TypeError):  # no C library to ask
        return None


_prctl = _load_prctl()


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


def _pool_worker() -> None:
    """The start of a local worker process: BLAS pinned, and SIGTERM back to ending it (a fork inherits the
    handler by which the build turns SIGTERM into an interruption; the pool ends its workers with SIGTERM)."""
    _pin_blas_threads()
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


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
        with ProcessPoolExecutor(max_workers=jobs, initializer=_pool_worker) as pool:
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


class Beside:
    """A forked process that makes calls beside this one, in the order they are handed to it.

    Forked, it starts at once with everything this process has loaded (a model's compiled code included), as
    it is when `start` returns. `Beside.start()` gives None where a fork is unsafe: while another thread runs
    here (a fork copies the locks it may hold), where the system cannot fork, or where it will not now (no
    memory, too many processes)."""

    def __init__(self, pool: ProcessPoolExecutor):
        self._pool = pool

    @classmethod
    def start(cls) -> Beside | None:
        """A new process beside this one, forked now, or None where forking is unsafe or fails."""
        if threading.active_count() > 1 or "fork" not in multiprocessing.get_all_start_methods():
            return None
        pool = ProcessPoolExecutor(
            max_workers=1, mp_context=multiprocessing.get_context("fork"), initializer=_beside, initargs=(os.getpid(),)
        )
        try:
            pool.submit(int)  # the pool forks at its first call, here rather than wherever a caller makes one
        except OSError:
            pool.shutdown(wait=False, cancel_futures=True)
            return None
        return cls(pool)

    def submit(self, fn, /, *args) -> Future:
        """Hand over `fn(*args)`; its future answers once the calls handed over before it are made (or, the
        process gone, holds the error at once: every caller then does the work itself)."""
        try:
            return self._pool.submit(fn, *args)
        except BrokenProcessPool as gone:
            future: Future = Future()
            future.set_exception(gone)
            return future

    def stop(self) -> None:
        """End the process: the calls not yet made are dropped, the one running (if any) is ended; returns
        once the pool's own threads have ended too."""
        # Details of the pool's: its processes, and the thread that manages them (shutdown forgets both).
        processes = list((getattr(self._pool, "_processes", None) or {}).values())
        manager = getattr(self._pool, "_executor_manager_thread", None)
        self._pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.terminate()
        if manager is not None:
            manager.join()


def _beside(parent: int) -> None:
    """The start of a process beside `parent`: BLAS pinned to one thread, Ctrl-C left to `parent` (which ends it),
    and (on Linux) killed when `parent` ends.

    A parent killed without a word (SIGTERM, SIGKILL) would otherwise leave it waiting for calls for ever: it holds
    its own copy of its queue's pipe, so it never reads the end of it. Elsewhere such a process lingers. The signal
    comes when the thread that forked it ends: the only thread of `parent` (see `Beside.start`)."""
    _pool_worker()  # `stop` terminates it with SIGTERM, whatever the parent handles
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # else a Ctrl-C while it waits prints its traceback
    _end_with(parent)


def _end_with(parent: int) -> None:
    """(On Linux) have this process killed when `parent` ends, or end it now if `parent` already has."""
    if _prctl is not None:
        _prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)  # refused only in a sandbox: then it may linger, as elsewhere
        if os.getppid() != parent:  # the parent ended before the call above
            os._exit(1)


class Background:
    """One call running in a new Python process while this one goes on; `result()` waits for it.

    The process is a fresh interpreter: not a fork (which would copy the locks of this process's threads)
    and not multiprocessing's spawn (which runs the caller's main script again). It is handed this
    process's import path and the call, pickled, and answers on a pipe of its own. A call that cannot be
    pickled raises here, before any process starts.
    """

    def __init__(self, function, *args):
        call = pickle.dumps(sys.path) + pickle.dumps((function, args))  # the path first: the call is found through it
        read, write = os.pipe()
        self._answer = os.fdopen(read, "rb")
        # -P: the current folder does not come first on the path, where a file of its could shadow a module.
        # A process group of its own: a Ctrl-C at the terminal reaches this process only, which ends the call
        # (`stop`), rather than interrupting the new interpreter while it starts (and printing its traceback).
        self._process = subprocess.Popen(
            [sys.executable, "-P", "-c", _CHILD, str(write), str(os.getpid())],
            stdin=subprocess.PIPE,
            pass_fds=(write,),
            process_group=0,
        )
        os.close(write)
        with self._process.stdin as calls:
            calls.write(call)

    def finished(self, timeout: float) -> bool:
        """Whether the call has answered (or its process ended), after waiting at most `timeout` seconds."""
        poller = select.poll()
        poller.register(self._answer, select.POLLIN)
        return bool(poller.poll(timeout * 1000))

    def result(self):
        """What the call returned; raises BackgroundFailed if it raised, its process ended without answering,
        or it was stopped."""
        if self._answer.closed:
            raise BackgroundFailed(f"it was stopped (its process ended with code {self._process.returncode})")
        try:
            done, value = pickle.load(self._answer)
        except EOFError:
            done, value = False, f"its process ended with code {self._process.wait()}"
        finally:
            self._answer.close()
        self._process.wait()
        if not done:
            raise BackgroundFailed(value)
        return value

    def stop(self) -> None:
        """End the call if it still runs (its result is no longer wanted)."""
        if self._process.poll() is None:
            self._process.terminate()
        self._process.wait()
        self._answer.close()


class BackgroundFailed(Exception):
    """A call in the background raised (its type and message) or its process died."""


_CHILD = """import pickle, sys
sys.path[:] = pickle.load(sys.stdin.buffer)
from sitegen.compute.executors import answer_call
answer_call(sys.stdin.buffer, int(sys.argv[1]), int(sys.argv[2]))
"""


def answer_call(calls, answer_fd: int, caller: int) -> None:
    """In a Background's process: read the call from `calls`, make it, and write its outcome to `answer_fd`;
    killed, on Linux, when `caller` ends (even by SIGKILL), rather than working on for nobody."""
    _end_with(caller)
    try:
        function, args = pickle.load(calls)
        outcome = (True, function(*args))
    except BaseException as error:  # reported to the waiting process, which decides what to do
        outcome = (False, f"{type(error).__name__}: {error}")
    try:
        with os.fdopen(answer_fd, "wb") as answer:
            pickle.dump(outcome, answer)
    except BrokenPipeError:  # the waiting process has gone; what the call left behind (a cache) still serves
        pass
