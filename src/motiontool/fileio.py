"""Files: atomic saves, bounded reads and the words for what went wrong (docs/decisions.md R1-R9).

Saves write a temporary file beside the target, fsync and rename, so a file is never half-written; the target keeps
its mode (a new file gets the umask's), a symbolic link stays a link and its target is replaced, and temporary files
that a killed save left behind (our own name pattern only) are removed by the next save of the same file. Reads
refuse what is not a regular file (a device or pipe would never end) and files beyond a size limit per format.
"""

from __future__ import annotations

import contextlib
import errno
import os
import re
import secrets
import stat
import threading
import time
from pathlib import Path

MiB = 1 << 20
# Temporary files of a save: ".NAME.PID-RANDOM.tmp" beside the target (older versions wrote ".NAME.XXXXXXXX.tmp").
_TEMP = re.compile(r"\.(?P<name>.+)\.(?:(?P<pid>[0-9]{1,10})-[0-9a-f]{8}|[a-z0-9_]{8})\.tmp", re.ASCII)
STALE_DEAD_WRITER_S = 60      # a temp file whose writer (this machine) is gone, untouched this long, is stale
STALE_ANY_S = 24 * 3600       # any temp file of ours untouched this long is stale (writer elsewhere or unknown)
_umask_lock = threading.Lock()


class FileRefused(OSError):
    """A file a reader will not read (not a regular file, too large): ``strerror`` says why in words."""


def reason(exc: OSError) -> str:
    """The operating system's words for an error ("No such file or directory"), without the path."""
    return exc.strerror or str(exc)


def write_error(path: Path | str, exc: OSError) -> str:
    """The one message for a failed save: ``cannot write PATH: reason``."""
    return f"cannot write {path}: {reason(exc)}"


# --- reading -----------------------------------------------------------------------------------------------------
def read_bytes(path: Path | str, limit: int, what: str = "file") -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes; raises FileRefused (an OSError) for anything else,
    so that a device, a pipe or a runaway file can never stall or exhaust the reader."""
    path = Path(path)
    _refuse_irregular(path, os.stat(path).st_mode)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
    fd = os.open(path, flags)
    with os.fdopen(fd, "rb") as f:
        info = os.fstat(f.fileno())  # the file that was opened, not the one stat saw
        _refuse_irregular(path, info.st_mode)
        if info.st_size > limit:
            raise _too_large(path, info.st_size, limit, what)
        data = f.read(info.st_size + 1)  # not read(limit + 1): that allocates the whole limit (1 GiB for .zbo)
        if len(data) > info.st_size:  # it grows while we read: at most to the limit
            data += f.read(limit + 1 - len(data))
    if len(data) > limit:  # it grew while we read
        raise _too_large(path, len(data), limit, what)
    return data


def read_text(path: Path | str, limit: int, what: str = "file", encoding: str = "utf-8") -> str:
    return read_bytes(path, limit, what).decode(encoding)


def _refuse_irregular(path: Path, mode: int) -> None:
    if stat.S_ISDIR(mode):
        raise FileRefused(errno.EISDIR, os.strerror(errno.EISDIR), str(path))
    if not stat.S_ISREG(mode):
        raise FileRefused(errno.EINVAL, "not a regular file (a device, pipe or socket)", str(path))


def _too_large(path: Path, size: int, limit: int, what: str) -> FileRefused:
    return FileRefused(errno.EFBIG, f"{_size(size)}, more than the {_size(limit)} a {what} may have", str(path))


def _size(n: int) -> str:
    return f"{n / MiB:.0f} MiB" if n >= MiB else f"{n} bytes"  # limits are whole MiB


# --- writing -----------------------------------------------------------------------------------------------------
def real_target(path: Path | str) -> Path:
    """Where a save of ``path`` lands: through symbolic links (also one whose target does not exist yet)."""
    path = Path(path)
    return Path(os.path.realpath(path)) if path.is_symlink() else path


def check_writable(path: Path | str) -> None:
    """Raise the OSError a save of ``path`` would meet (missing folder, a folder or device in the way, no
    permission, read-only file system) before any work is done; a trial file is created and removed."""
    target = real_target(path)
    _existing(target)
    fd, tmp = _create_temp(target.parent, target.name)
    os.close(fd)
    os.unlink(tmp)


def _existing(target: Path) -> os.stat_result | None:
    """The target's status, None when it does not exist yet; a folder or device in the way is refused (a save must
    never rename over one)."""
    try:
        info = os.stat(target)
    except FileNotFoundError:
        return None
    _refuse_irregular(target, info.st_mode)
    return info


class AtomicFile:
    """A file written piece by piece (a streamed trace) that appears at its path only when complete: ``commit``
    renames it into place, ``discard`` (or an exception inside ``with``) removes it and leaves the old file."""

    def __init__(self, path: Path | str, text: bool = True, encoding: str = "utf-8"):
        self.path = Path(path)
        self.target = real_target(path)
        self._info = _existing(self.target)
        self._mode = stat.S_IMODE(self._info.st_mode) if self._info is not None else 0o666 & ~_umask()
        remove_stale_temps(self.target)
        fd, self.tmp = _create_temp(self.target.parent, self.target.name)
        self.file = os.fdopen(fd, "w", encoding=encoding, newline="") if text else os.fdopen(fd, "wb")

    def write(self, data) -> None:
        self.file.write(data)

    def commit(self) -> None:
        try:
            self.file.flush()
            _keep_owner_and_mode(self.file.fileno(), self.tmp, self._info, self._mode)
            os.fsync(self.file.fileno())
            self.file.close()
            os.replace(self.tmp, self.target)
        except BaseException:
            self.discard()
            raise
        _sync_folder(self.target.parent)

    def discard(self) -> None:
        with contextlib.suppress(OSError):
            self.file.close()
        with contextlib.suppress(OSError):
            os.unlink(self.tmp)

    def __enter__(self) -> AtomicFile:
        return self

    def __exit__(self, kind, exc, tb) -> None:
        if kind is None:
            self.commit()
        else:
            self.discard()


def atomic_write_bytes(path: Path | str, data: bytes) -> None:
    """Write ``data`` to ``path`` so that the file is either the old or the new one, never a mixture."""
    with AtomicFile(path, text=False) as f:
        f.write(data)


def atomic_write_text(path: Path | str, text: str, encoding: str = "utf-8") -> None:
    atomic_write_bytes(path, text.encode(encoding))


def _create_temp(folder: Path, name: str) -> tuple[int, str]:
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0) | getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        tmp = os.path.join(folder or ".", f".{name}.{os.getpid()}-{secrets.token_hex(4)}.tmp")
        try:
            return os.open(tmp, flags, 0o600), tmp
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "no free temporary file name", str(folder))


def _keep_owner_and_mode(fd: int, tmp: str, info: os.stat_result | None, mode: int) -> None:
    if info is not None and hasattr(os, "fchown") and info.st_gid != os.getegid():
        with contextlib.suppress(OSError):  # the group of a shared file, where we may set it
            os.fchown(fd, -1, info.st_gid)
    if hasattr(os, "fchmod"):
        os.fchmod(fd, mode)
    else:  # Windows: only the read-only bit exists
        os.chmod(tmp, mode)


def _umask() -> int:
    """The process's umask: what a plain ``open(path, "w")`` would give a new file."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    with _umask_lock:  # no way to read it without setting it elsewhere
        mask = os.umask(0o022)
        os.umask(mask)
    return mask


def _sync_folder(folder: Path) -> None:
    """Make the rename itself durable (POSIX; not possible and not needed on Windows)."""
    try:
        dir_fd = os.open(folder or ".", os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(dir_fd)
    except OSError:
        pass
    finally:
        os.close(dir_fd)


def remove_stale_temps(target: Path | str) -> list[Path]:
    """Delete temporary files a killed save of ``target`` left beside it (our own name pattern only): those whose
    writer on this machine no longer runs and that were not touched for a minute, and any older than a day."""
    target = Path(target)
    removed: list[Path] = []
    now = time.time()
    try:
        candidates = list(target.parent.glob(f".{glob_escape(target.name)}.*.tmp"))
    except OSError:
        return removed
    for tmp in candidates:
        m = _TEMP.fullmatch(tmp.name)
        if m is None or m.group("name") != target.name:
            continue
        try:
            age = now - tmp.lstat().st_mtime
        except OSError:
            continue
        pid = int(m.group("pid")) if m.group("pid") else None
        dead = pid is not None and not _pid_alive(pid)
        if (dead and age > STALE_DEAD_WRITER_S) or age > STALE_ANY_S or (pid is None and age > 3600):
            with contextlib.suppress(OSError):
                tmp.unlink()
                removed.append(tmp)
    return removed


def glob_escape(name: str) -> str:
    return re.sub(r"([*?\[])", r"[\1]", name)


def _pid_alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    if os.name == "nt":  # no cheap test: leave it to the age rule
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return True
    return True


def filter_extension(name_filter: str) -> str:
    """The first extension of a file dialog's name filter, without the dot: "APOSS programs (*.m)" → "m",
    "CSV (*.csv *.txt)" → "csv"; "" for "All files (*)". A save dialog adds it to a name typed without one, so
    the file is not then hidden by File ▸ Open's filter (issue 23 item 9)."""
    found = re.search(r"\*\.([A-Za-z0-9_]+)", name_filter)
    return found.group(1) if found else ""
