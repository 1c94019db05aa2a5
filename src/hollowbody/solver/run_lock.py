"""One run at a time in an output folder.

A run writes its histories, states, restart files and summary into its folder
as it goes. A second run started in the same folder while the first is still
going (a ``--resume`` typed in another terminal, a batch job requeued while the
first copy still runs, ``--overwrite`` on the wrong folder) would delete or
interleave the first one's files. So a run holds a lock file in its folder,
:data:`LOCK_NAME`, from before it writes anything until it has written its
summary; the file says which process on which machine holds it and since when.

Another run asking for the folder is refused (:class:`~hollowbody.errors.UserInputError`,
nothing touched) while that process is alive. A lock left by a process that no
longer exists (killed, machine rebooted) is taken over, and the run's log says
so. A lock written on another machine (a shared file system) cannot be checked:
it is refused, and the message names the file to delete if that run is over.
"""

from __future__ import annotations

import json
import os
import socket
import time
from pathlib import Path

from hollowbody.errors import UserInputError

#: The lock file a run keeps in its output folder while it runs.
LOCK_NAME = ".hollowbody-run.lock"
#: An empty lock file younger than this (s) is one being written, not a stale one.
_FRESH_SECONDS = 10.0


def _start_ticks(pid: int) -> int | None:
    """Start time of process ``pid`` in clock ticks after boot (Linux), else None."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    try:  # the command name (field 2) is in parentheses and may hold spaces
        return int(stat[stat.rindex(")") + 2:].split()[19])
    except (ValueError, IndexError):
        return None


def _alive(pid: int, ticks: int | None) -> bool:
    """Whether process ``pid`` (started at ``ticks``, when known) still runs here."""
    if pid <= 0:
        return False
    if os.name == "nt":  # no signal 0 there: assume it runs (the message says what to do)
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    now = _start_ticks(pid)
    return ticks is None or now is None or now == ticks  # a reused pid is another process


def _holder(path: Path) -> dict | None:
    """The lock's contents, or None when there is no lock file."""
    try:
        text = path.read_text()
    except (FileNotFoundError, NotADirectoryError):  # no lock (or no folder) there
        return None
    except OSError as exc:
        raise UserInputError(f"{path}: cannot read the run lock ({exc.strerror})") from None
    try:
        data = json.loads(text)
    except ValueError:
        data = None
    return data if isinstance(data, dict) else {}


def _busy(out: Path, path: Path, info: dict) -> str | None:
    """Why ``out`` cannot be used now (a live holder), or None (no holder, or a stale one)."""
    if not info:  # empty or damaged: a run that is just writing it, or a stale one
        try:
            fresh = time.time() - path.stat().st_mtime < _FRESH_SECONDS
        except OSError:
            fresh = False
        return (f"{out} is in use by another hollowbody run that is just starting: wait "
                "for it to end or choose another output folder") if fresh else None
    host = info.get("host")
    pid = int(info.get("pid", -1)) if str(info.get("pid", "")).lstrip("-").isdigit() else -1
    since = info.get("started", "an unknown time")
    if pid == os.getpid() and host == socket.gethostname():
        return None  # this process's own lock (a run left without releasing it)
    if host and host != socket.gethostname():
        return (f"{out} is in use by a hollowbody run on {host} (process {pid}, started "
                f"{since}): wait for it to end or choose another output folder; if that "
                f"run is over, delete {path}")
    if host and _alive(pid, info.get("ticks")):
        unsure = f"; if no such run is going on, delete {path}" if os.name == "nt" else ""
        return (f"{out} is in use by another hollowbody run (process {pid}, started "
                f"{since}): wait for it to end, stop it (Ctrl-C or SIGTERM: it keeps its "
                f"results and restart file), or choose another output folder{unsure}")
    return None


def check_free(out: Path) -> None:
    """UserInputError when a live run holds ``out`` (reads only; see :class:`RunLock`)."""
    path = Path(out) / LOCK_NAME
    info = _holder(path)
    if info is not None:
        why = _busy(Path(out), path, info)
        if why:
            raise UserInputError(why)


class RunLock:
    """Hold ``out`` for this process: ``with RunLock(out) as lock: ...``.

    Creates the folder when needed. ``stale`` is the description of a stale lock
    that was taken over (for the run's log), else None. Raises UserInputError
    when a live run holds the folder or the lock cannot be written.
    """

    def __init__(self, out: Path) -> None:
        self.out = Path(out)
        self.path = self.out / LOCK_NAME
        self.stale: str | None = None
        self._held = False

    def __enter__(self) -> RunLock:
        self.acquire()
        return self

    def __exit__(self, *exc: object) -> None:
        self.release()

    def acquire(self) -> None:
        if self.out.exists() and not self.out.is_dir():
            raise UserInputError(f"{self.out} is a file, not an output folder")
        try:
            self.out.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise UserInputError(f"{self.out}: cannot create the output folder "
                                 f"({exc.strerror})") from None
        me = {"pid": os.getpid(), "host": socket.gethostname(),
              "started": time.strftime("%Y-%m-%d %H:%M:%S"),
              "ticks": _start_ticks(os.getpid())}
        for _ in range(3):  # another process may take or drop it in between
            try:
                fd = os.open(self.path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            except FileExistsError:
                info = _holder(self.path)
                if info is None:
                    continue  # dropped in between: try again
                why = _busy(self.out, self.path, info)
                if why:
                    raise UserInputError(why) from None
                self.stale = (f"a stale run lock (process {info.get('pid', '?')}, started "
                              f"{info.get('started', '?')}, no longer running) was taken over")
                try:
                    self.path.unlink()
                except FileNotFoundError:
                    pass
                continue
            except OSError as exc:
                raise UserInputError(f"{self.path}: cannot write the run lock "
                                     f"({exc.strerror})") from None
            with os.fdopen(fd, "w") as fh:
                json.dump(me, fh)
            self._held = True
            return
        raise UserInputError(f"{self.out}: another process keeps taking the run lock "
                             f"{LOCK_NAME}; choose another output folder")

    def release(self) -> None:
        """Delete the lock file if this process holds it."""
        if not self._held:
            return
        self._held = False
        info = _holder(self.path)
        if info is not None and info.get("pid") == os.getpid():
            try:
                self.path.unlink()
            except FileNotFoundError:
                pass
