"""Where work runs: in this process, in a pool of local processes, or on a Dask cluster.

Each is a `concurrent.futures.Executor`. The build submits pure functions of their arguments and folds
their results in plan order, so the output is the same byte for byte whichever runs them.
"""

from __future__ import annotations

import importlib
import multiprocessing
import os
from collections.abc import Iterator
from concurrent.futures import Executor, Future, ProcessPoolExecutor
from contextlib import contextmanager

AUTO = "auto"  # --jobs auto: a worker per core of this machine


class InProcess(Executor):
    """Runs each call in this process, when its result is first asked for.

    Deferred rather than run at `submit`: a build submits a book's work at once, and then holds only the
    results of the page it is on, as a build without an executor would."""

    def submit(self, fn, /, *args, **kwargs) -> Future:
        """`fn(*args, **kwargs)`, to be run when its future's result is asked for."""
        return _Deferred(fn, args, kwargs)


class _Deferred(Future):
    """A future whose call runs in the thread that first asks for its result."""

    def __init__(self, fn, args, kwargs):
        super().__init__()
        self._call = (fn, args, kwargs)

    def result(self, timeout=None):
        """Run the call (the first time), then its value, or raise what it raised."""
        self._run()
        return super().result(timeout)

    def exception(self, timeout=None):
        """Run the call (the first time), then what it raised, or None."""
        self._run()
        return super().exception(timeout)

    def _run(self) -> None:
        if self._call is None or not self.set_running_or_notify_cancel():
            return
        (fn, args, kwargs), self._call = self._call, None
        try:
            self.set_result(fn(*args, **kwargs))
        except BaseException as error:  # raised to whoever reads the result, as a pool would
            self.set_exception(error)


def result_here_if_waiting(executor: Executor, future: Future, fn, *args):
    """`future`'s result, where `future` is `executor.submit(fn, *args)`; should no local worker have started it
    yet, it is cancelled and `fn(*args)` runs in this process, which would only wait for it (the same value, as
    the work is a pure function of its arguments). On a cluster the future is left to it."""
    if isinstance(executor, (InProcess, ProcessPoolExecutor)) and future.cancel():
        return fn(*args)
    return future.result()


def worker_count(jobs: int | str) -> int:
    """The number of local workers `--jobs` asks for (`auto`: one per core this process may use)."""
    if jobs == AUTO:
        return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    return int(jobs)


def start_worker(setup=None, modules=()) -> None:
    """What a worker process does before its first call: BLAS on one thread (small linear algebra is ~10x
    faster so, and workers must not oversubscribe cores), then `setup()` if given, then import `modules`."""
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    os.environ["OMP_NUM_THREADS"] = "1"
    if setup is not None:
        setup()
    for name in modules:
        importlib.import_module(name)


@contextmanager
def executor_for(jobs: int | str = 1, scheduler: str | None = None, setup=None, modules=()) -> Iterator[Executor]:
    """This process, a pool of `jobs` local processes, or a Dask cluster's executor; shut down after.

    `setup`: a picklable call that every worker makes before its work (the book's models made importable);
    `modules`: what every worker imports then (the models' modules), while this process reads the book."""
    if scheduler:
        yield from _dask_executor(scheduler, setup, tuple(modules))
    elif worker_count(jobs) > 1:
        # New interpreters ("spawn"): they start with nothing of this process (its threads, locks and heap),
        # import what the work needs, and load the compiled kernels from their cache.
        context = multiprocessing.get_context("spawn")
        count = worker_count(jobs)
        pool = ProcessPoolExecutor(
            count, mp_context=context, initializer=start_worker, initargs=(setup, tuple(modules))
        )
        for _ in range(count):  # a pool starts a process per call while none is idle: all of them now
            pool.submit(int)
        try:
            yield pool
        finally:  # a build that stops early does not wait for the work it no longer wants
            pool.shutdown(wait=True, cancel_futures=True)
    else:
        yield InProcess()


def _dask_executor(scheduler: str, setup, modules: tuple[str, ...]) -> Iterator[Executor]:
    try:
        from distributed import Client
        from distributed.diagnostics.plugin import WorkerPlugin
    except ImportError:
        raise RuntimeError("--scheduler needs Dask: pip install -e '.[dask]'") from None

    class StartWorker(WorkerPlugin):
        """`start_worker(setup)` on every worker of the cluster, those that join later too."""

        def setup(self, worker) -> None:
            start_worker(setup, modules)

    with Client(scheduler) as client:
        # Named by what it sets up: a build with other models registers anew, the same ones do not.
        client.register_plugin(StartWorker(), name=f"sitegen-start-worker-{getattr(setup, 'digest', '')}")
        executor = client.get_executor()
        try:
            yield executor
        finally:
            executor.shutdown(wait=False)  # the client's end cancels what is left
