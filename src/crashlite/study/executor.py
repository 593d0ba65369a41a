"""Where designs run: a Dask LocalCluster (default), an existing Dask
scheduler, a Dask cluster object (a batch system's through dask-jobqueue:
``SLURMCluster``, ``PBSCluster``, ``LSFCluster``; passed from Python or
named ``"module:callable"`` in the study file), or in this process
(``serial``, for debugging and small tests).

Workers are processes, each running one design at a time single-threaded
(``NUMBA_NUM_THREADS=threads_per_run``). A worker that dies mid-run (killed,
out of memory) is restarted by its nanny and the scheduler gives its design
to another worker; a design that kills ``allowed_failures`` workers is
reported failed. Designs read and write the study folder, so with a remote
scheduler it must lie on a file system the workers share.

Ctrl-C: the study's driver stops the designs and closes the cluster; the
LocalCluster's workers ignore SIGINT themselves (a terminal sends it to
every process of the foreground group), so that they are stopped by the
driver, not killed half-way with a traceback each.
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
                except KeyboardInterrupt:  # Ctrl-C stops the study, it is not the design's result
                    raise
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

    def __init__(
        self,
        workers: int = 0,
        threads: int = 1,
        address: str | None = None,
        allowed_failures: int = 3,
        memory_limit: str = "auto",
        dashboard: bool = False,
        cluster=None,
    ):
        if workers < 0:  # a LocalCluster of -4 workers waits for them forever
            raise ValueError(f"workers must be 1 or more (0: one per core), got {workers}")
        if cluster is not None and address:
            raise ValueError("give a scheduler address or a cluster, not both")
        if cluster is not None and not isinstance(cluster, str) and not hasattr(cluster, "scheduler_address"):
            raise TypeError(
                f"cluster: {type(cluster).__name__} has no scheduler_address (a Dask cluster such as "
                'dask-jobqueue\'s SLURMCluster, or "module:callable" returning one)'
            )
        self.workers = workers or (os.cpu_count() or 1)
        self.threads = threads
        self.address = address
        self.cluster_spec = cluster  # an object with scheduler_address, or "module:callable"
        self.owned_cluster = None  # a cluster made here from "module:callable": closed at the end
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

        self._config = dask.config.set(
            {"distributed.scheduler.allowed-failures": self.allowed_failures, "distributed.admin.tick.limit": "30s"}
        )
        self._config.__enter__()
        env = {
            "NUMBA_NUM_THREADS": str(self.threads),
            "OMP_NUM_THREADS": str(self.threads),
            "MKL_NUM_THREADS": str(self.threads),
            "OPENBLAS_NUM_THREADS": str(self.threads),
        }
        try:
            if self.cluster_spec is not None:
                self.address = _scheduler_address(self._cluster())
                self.client = Client(self.address, timeout="30s")
            elif self.address:
                self.client = Client(self.address, timeout="30s")
            else:
                self.cluster = LocalCluster(
                    n_workers=self.workers,
                    threads_per_worker=1,
                    processes=True,
                    memory_limit=self.memory_limit,
                    env=env,
                    dashboard_address=":0" if self.dashboard else None,
                    silence_logs=40,
                    preload=["crashlite.study.interrupts"],
                )
                self.client = Client(self.cluster)
        except KeyboardInterrupt as e:  # Ctrl-C while the cluster starts: close what started
            self.__exit__(type(e), e, e.__traceback__)
            raise
        except Exception as e:
            self.__exit__(None, None, None)
            where = self.address or (
                f"the cluster {self._cluster_name()}" if self.cluster_spec is not None else "a LocalCluster"
            )
            raise ExecutorError(f"cannot start Dask on {where}: {type(e).__name__}: {e}") from e
        return self

    def __exit__(self, *exc):
        from .interrupts import held_interrupts

        # after Ctrl-C: within seconds (the workers are killed if they do not stop)
        quick = bool(exc) and exc[0] is not None and issubclass(exc[0], KeyboardInterrupt)
        with held_interrupts(drop=True):
            self._close(quick)
        return False

    def _close(self, quick: bool) -> None:
        try:
            if self.client is not None:
                self.client.close(timeout=3 if quick else 10)
        except Exception:  # noqa: BLE001
            pass
        try:
            if self.cluster is not None:
                self.cluster.close(timeout=5 if quick else 20)
        except Exception:  # noqa: BLE001
            pass
        try:
            if self.owned_cluster is not None:
                self.owned_cluster.close()
        except Exception:  # noqa: BLE001
            pass
        self.client = self.cluster = self.owned_cluster = None
        cfg = getattr(self, "_config", None)
        if cfg is not None:
            cfg.__exit__(None, None, None)
            self._config = None

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

    def _cluster(self):
        """The cluster object (made from "module:callable" the first time)."""
        spec = self.cluster_spec
        if not isinstance(spec, str):
            return spec
        if self.owned_cluster is None:
            import importlib

            module, _, name = spec.partition(":")
            try:
                make = getattr(importlib.import_module(module.strip()), name.strip())
            except (ImportError, AttributeError) as e:
                raise ExecutorError(f"cluster = {spec!r}: {type(e).__name__}: {e}") from None
            self.owned_cluster = make() if callable(make) else make
        return self.owned_cluster

    def _cluster_name(self) -> str:
        spec = self.cluster_spec
        return repr(spec) if isinstance(spec, str) else type(spec).__name__

    def describe(self) -> str:
        if self.cluster_spec is not None:
            return f"Dask cluster {self._cluster_name()} (scheduler {self.address})"
        if self.address:
            return f"Dask scheduler {self.address}"
        return (
            f"Dask LocalCluster, {self.workers} worker process{'es' if self.workers > 1 else ''}, "
            f"{self.threads} thread{'s' if self.threads > 1 else ''} per run"
        )

    def worker_pids(self) -> dict:
        """Worker address -> process ID."""
        return self.client.run(os.getpid)


def _scheduler_address(cluster) -> str:
    address = cluster if isinstance(cluster, str) else getattr(cluster, "scheduler_address", None)
    if not isinstance(address, str) or not address:
        raise ExecutorError(f"the cluster {type(cluster).__name__} gives no scheduler_address")
    return address


def make_executor(
    execution, scheduler: str | None = None, workers: int | None = None, serial: bool = False, cluster=None
):
    """The executor a study runs on (CLI options override the file's;
    ``cluster``, a Dask cluster object or "module:callable", overrides the
    file's scheduler and cluster)."""
    if serial:
        return SerialExecutor(execution.threads_per_run)
    if cluster is None and scheduler is None:
        cluster = getattr(execution, "cluster", None)
    return DaskExecutor(
        workers=workers or execution.workers,
        threads=execution.threads_per_run,
        address=None if cluster is not None else (scheduler or execution.scheduler),
        allowed_failures=execution.allowed_failures,
        memory_limit=execution.memory_limit,
        cluster=cluster,
    )
