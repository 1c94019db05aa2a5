"""One run at a time in an output folder.

A run writes its histories, states, restart files and summary into its folder
as it goes. A second run started in the same folder while the first is still
going (a ``--resume`` typed in another terminal, a batch job requeued while the
first copy still runs, ``--overwrite`` on the wrong folder) would delete or
interleave the first one's files. So whatever writes a run folder (a run, the
set-up and post-processing around it) holds the folder's lock file,
:data:`LOCK_NAME`, for as long as it writes there.

The lock is the operating system's file lock (``flock``) on that file: it
belongs to the holding process and goes when that process ends, however it
ends (a killed run leaves no lock to clean up, and a process id used again by
another program means nothing). The file also says which process on which
machine holds it and since when, for the message. Another process asking for a
held folder is refused (:class:`~hollowbody.errors.UserInputError`, nothing in
the folder touched); a file left by a process that no longer runs is taken
over, and the run's log says so. Within one process the lock is re-entrant (a
validation holds the folder around the run, which takes it again).

On a platform without ``fcntl`` (Windows) folders are not locked.
"""

from __future__ import annotations

import json
import os
import socket
import time
from pathlib import Path

from hollowbody.errors import UserInputError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None

#: The lock file a run keeps in its output folder while it runs.
LOCK_NAME = ".hollowbody-run.lock"

#: This process's held locks: resolved lock path -> [file descriptor, depth].
_HELD: dict[str, list[int]] = {}


def _key(path: Path) -> str:
    return str(path.resolve())


def _read(fd: int) -> dict:
    """The JSON written in the open lock file ``fd`` ({} when empty or damaged)."""
    try:
        os.lseek(fd, 0, os.SEEK_SET)
        data = json.loads(os.read(fd, 4096).decode() or "{}")
    except (OSError, ValueError, UnicodeDecodeError):
        return {}
    return data if isinstance(data, dict) else {}


def _busy_message(out: Path, info: dict) -> str:
    host = info.get("host")
    where = f" on {host}" if host and host != socket.gethostname() else ""
    return (f"{out} is in use by another hollowbody run{where} (process "
            f"{info.get('pid', '?')}, started {info.get('started', 'just now')}): wait for "
            "it to end, stop it (Ctrl-C or SIGTERM: it keeps its results and restart "
            "file), or choose another output folder")


def check_free(out: Path) -> None:
    """UserInputError when another process holds ``out`` (reads only; see :class:`RunLock`)."""
    path = Path(out) / LOCK_NAME
    if fcntl is None or _key(path) in _HELD:
        return
    try:
        fd = os.open(path, os.O_RDONLY)
    except (FileNotFoundError, NotADirectoryError):  # no lock (or no folder) there
        return
    except OSError as exc:
        raise UserInputError(f"{path}: cannot read the run lock ({exc.strerror})") from None
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
        except BlockingIOError:
            raise UserInputError(_busy_message(Path(out), _read(fd))) from None
        fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        os.close(fd)


class RunLock:
    """Hold ``out`` for this process: ``with RunLock(out) as lock: ...``.

    Creates the folder when needed. ``stale`` is the description of a lock file
    of a process that no longer runs, taken over (for the run's log), else None.
    Raises UserInputError when another process holds the folder or the lock
    cannot be written.
    """

    def __init__(self, out: Path) -> None:
        self.out = Path(out)
        self.path = self.out / LOCK_NAME
        self.stale: str | None = None
        self._key: str | None = None

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
        key = _key(self.path)
        if key in _HELD:  # this process holds it already (a run inside a validation)
            _HELD[key][1] += 1
            self._key = key
            return
        if fcntl is None:  # pragma: no cover - Windows
            return
        for _ in range(5):
            try:
                fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
            except OSError as exc:
                raise UserInputError(f"{self.path}: cannot write the run lock "
                                     f"({exc.strerror})") from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                info = _read(fd)
                os.close(fd)
                raise UserInputError(_busy_message(self.out, info)) from None
            try:  # the file may have been deleted and made anew since it was opened
                same = os.stat(self.path).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if not same:
                os.close(fd)
                continue
            old = _read(fd)
            if old.get("pid") is not None:
                self.stale = (f"a run lock left by process {old.get('pid')} (started "
                              f"{old.get('started', '?')}), which no longer runs, was "
                              "taken over")
            me = {"pid": os.getpid(), "host": socket.gethostname(),
                  "started": time.strftime("%Y-%m-%d %H:%M:%S")}
            try:
                os.ftruncate(fd, 0)
                os.lseek(fd, 0, os.SEEK_SET)
                os.write(fd, json.dumps(me).encode())
            except OSError:
                pass  # the lock holds without its description
            _HELD[key] = [fd, 1]
            self._key = key
            return
        raise UserInputError(f"{self.out}: another process keeps replacing the run lock "
                             f"{LOCK_NAME}; choose another output folder")

    def release(self) -> None:
        """Give the folder back (the outermost holder of this process deletes the file)."""
        key, self._key = self._key, None
        held = _HELD.get(key) if key is not None else None
        if held is None:
            return
        held[1] -= 1
        if held[1] > 0:
            return
        del _HELD[key]
        fd = held[0]
        try:
            if os.stat(self.path).st_ino == os.fstat(fd).st_ino:
                self.path.unlink()  # while still locked: a waiting process sees it gone
        except OSError:
            pass
        try:
            fcntl.flock(fd, fcntl.LOCK_UN)
        except OSError:
            pass
        os.close(fd)
