"""Ctrl-C in a study: the driver holds SIGINT back while it writes to the
study's database (a design is stored whole or not at all) and while it
closes the cluster after a first Ctrl-C; the workers of its LocalCluster
ignore SIGINT (a terminal sends it to every process of the foreground
group: the driver cancels their designs and closes them itself, a worker
killed by the same Ctrl-C would only add a traceback).
"""

from __future__ import annotations

import logging
import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def held_interrupts(drop: bool = False) -> Iterator[None]:
    """Ctrl-C (SIGINT) waits until the block is over, so that what it
    writes to the study's database is written whole; ``drop``: a Ctrl-C
    inside the block is dropped (the cleanup after a first one)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    got = []
    try:
        old = signal.signal(signal.SIGINT, lambda *_: got.append(1))
    except (ValueError, OSError):  # no signals here (an embedded interpreter)
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old if old is not None else signal.default_int_handler)
        if got and not drop and old is not signal.SIG_IGN:
            raise KeyboardInterrupt


def dask_setup(worker) -> None:
    """Dask preload of the LocalCluster's workers, called in each worker
    process as it starts: SIGINT is ignored there, and a failed heartbeat
    is not printed as a traceback (the driver closing the scheduler after
    Ctrl-C races the workers' heartbeats; a worker that truly lost its
    scheduler is closed by its nanny all the same)."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    logging.getLogger("distributed.worker").addFilter(_no_heartbeat_failure)


def _no_heartbeat_failure(record: logging.LogRecord) -> bool:
    return not str(record.msg).startswith("Failed to communicate with scheduler during heartbeat")
