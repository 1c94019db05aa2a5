"""dask worker preload: worker processes of a local cluster ignore Ctrl-C.

Ctrl-C in a terminal reaches every process of the foreground group; the
calibration's main process handles it (saves, closes the cluster). Without
this, every worker process would also die printing its own traceback.
"""

from __future__ import annotations

import signal
import threading


def dask_setup(worker: object) -> None:
    """Called by dask in each worker process at start-up."""
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGINT, signal.SIG_IGN)
