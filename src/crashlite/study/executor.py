"""Where designs run: a Dask LocalCluster (default), an existing Dask
scheduler, or in this process (``serial``, for debugging and small tests).

Workers are processes, each running one design at a time single-threaded
(``NUMBA_NUM_THREADS=threads_per_run``). A worker that dies mid-run (killed,
out of memory) is restarted by its nanny and the scheduler gives its design
to another worker; a design that kills ``allowed_failures`` workers is
reported failed. Designs read and write the study folder, so with a remote
scheduler it must lie on a file system the workers share.
"""

from __future__ import annotations

import os
import time
from concurrent.futures import Future


class ExecutorError(RuntimeError):
    """The cluster itself failed (not a design)."""


class SerialExecutor:
    """Runs each design in this process when it is waited for."""

    name = "serial"

    def __init__(self, threads: int = 1):
        self.threads = threads
        self.capacity = 1

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    started = True

    def submit(self, fn, arg):
        f = Future()
        f._crashlite_call = (fn, arg)  # run lazily, one at a time, in wait()
        return f

    def wait(self, handles, timeout: float):
        for h in handles:
            if not h.done():
                fn, arg = h._crashlite_call
                try:
                    h.set_result(fn(arg))
                except BaseException as e:  # noqa: BLE001
                    h.set_exception(e)
                return [h]
        return [h for h in handles if h.done()]

    def result(self, handle):
        return handle.result()

    def cancel(self, handles):
        pass

    def describe(self) -> str:
        return "serial (in this process)"

    def worker_pids(self) -> dict:
        return {"local": os.getpid()}


class DaskExecutor:
    """A Dask client over a LocalCluster of ``workers`` processes, or over
    the scheduler at ``address``."""

    name = "dask"

    def __init__(self, workers: int = 0, threads: int = 1, address: str | None = None,
                 allowed_failures: int = 3, memory_limit: str = "auto", dashboard: bool = False):
        if workers < 0:  # a LocalCluster of -4 workers waits for them forever
            raise ValueError(f"workers must be 1 or more (0: one per core), got {workers}")
        self.workers = workers or (os.cpu_count() or 1)
        self.threads = threads
        self.address = address
        self.allowed_failures = allowed_failures
        self.memory_limit = memory_limit
        self.dashboard = dashboard
        self.client = None
        self.cluster = None

    @property
    def started(self) -> bool:
        return self.client is not None

    def __enter__(self):
        import dask
        from distributed import Client, LocalCluster

        self._config = dask.config.set({"distributed.scheduler.allowed-failures": self.allowed_failures,
                                        "distributed.admin.tick.limit": "30s"})
        self._config.__enter__()
        env = {"NUMBA_NUM_THREADS": str(self.threads), "OMP_NUM_THREADS": str(self.threads),
               "MKL_NUM_THREADS": str(self.threads), "OPENBLAS_NUM_THREADS": str(self.threads)}
        try:
            if self.address:
                self.client = Client(self.address, timeout="30s")
            else:
                self.cluster = LocalCluster(n_workers=self.workers, threads_per_worker=1, processes=True,
                                            memory_limit=self.memory_limit, env=env,
                                            dashboard_address=":0" if self.dashboard else None,
                                            silence_logs=40)
                self.client = Client(self.cluster)
        except Exception as e:
            self.__exit__(None, None, None)
            where = self.address or "a LocalCluster"
            raise ExecutorError(f"cannot start Dask on {where}: {type(e).__name__}: {e}") from e
        return self

    def __exit__(self, *exc):
        try:
            if self.client is not None:
                self.client.close(timeout=10)
        except Exception:  # noqa: BLE001
            pass
        try:
            if self.cluster is not None:
                self.cluster.close(timeout=20)
        except Exception:  # noqa: BLE001
            pass
        self.client = self.cluster = None
        cfg = getattr(self, "_config", None)
        if cfg is not None:
            cfg.__exit__(None, None, None)
            self._config = None
        return False

    @property
    def capacity(self) -> int:
        """Task slots: the threads of the workers now connected."""
        try:
            info = self.client.scheduler_info(n_workers=-1) if self.client else {}
            n = sum(w.get("nthreads", 1) for w in info.get("workers", {}).values())
        except Exception:  # noqa: BLE001
            n = 0
        return max(n, 1 if self.address else self.workers)

    def submit(self, fn, arg):
        return self.client.submit(fn, arg, pure=False, key=f"design-{getattr(arg, 'key', '')}-{time.time_ns()}")

    def wait(self, handles, timeout: float):
        from distributed import wait

        if not handles:
            return []
        try:
            done, _ = wait(list(handles), timeout=timeout, return_when="FIRST_COMPLETED")
        except TimeoutError:
            return []
        except Exception as e:  # noqa: BLE001
            if "timeout" in type(e).__name__.lower():
                return []
            raise
        return list(done)

    def result(self, handle):
        return handle.result()

    def cancel(self, handles):
        try:
            self.client.cancel(list(handles), force=True)
        except Exception:  # noqa: BLE001
            pass

    def describe(self) -> str:
        if self.address:
            return f"Dask scheduler {self.address}"
        return f"Dask LocalCluster, {self.workers} worker process{'es' if self.workers > 1 else ''}, " \
               f"{self.threads} thread{'s' if self.threads > 1 else ''} per run"

    def worker_pids(self) -> dict:
        """Worker address -> process ID."""
        return self.client.run(os.getpid)


def make_executor(execution, scheduler: str | None = None, workers: int | None = None, serial: bool = False):
    """The executor a study runs on (CLI options override the file's)."""
    if serial:
        return SerialExecutor(execution.threads_per_run)
    return DaskExecutor(workers=workers or execution.workers, threads=execution.threads_per_run,
                        address=scheduler or execution.scheduler, allowed_failures=execution.allowed_failures,
                        memory_limit=execution.memory_limit)
