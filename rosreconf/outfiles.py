"""Write output files atomically, and never destroy what is not ours.

Pictures, launch files and configuration documents are read by other programs (a browser,
roslaunch, the next rosreconf run); a truncated file would be worse than none. Every writer
therefore goes through ``write_atomic``: the bytes land in a temporary file beside the target,
are flushed to disk, and only then renamed over it (``os.replace`` is atomic on POSIX).

A rename replaces whatever has the target's name, so one function, ``output_target``, first
decides what a path given with ``-o`` is, for every command:

- ``-`` is standard output (the CLI writes there itself);
- a path that is this process's own stdout or stderr (``/dev/stdout``, ``/dev/fd/2``,
  ``/proc/self/fd/1``, or any name of the same file as descriptor 1 or 2) is written to that
  descriptor, after what is already there: ``-o /dev/stdout >> log`` appends to the log. A
  rename would put a new file in the place of the log (the name resolves to it) and lose
  its content;
- a symlink is followed to the real path, so the link stays a link and its target is written;
- a regular file is replaced atomically and keeps its permission bits (a 0600 secret stays 0600);
- a new path is created with the usual permissions (0666 minus umask);
- a folder, a device (``/dev/full``), a FIFO, a socket or a symlink loop is refused with a
  ``UsageError`` (exit 2) naming what it is: replacing a device node by a regular file, or a
  FIFO whose reader then gets nothing, destroys something that was not ours.

Folders given with ``-o`` go through ``output_folder``, and a set of files that belong together
(a PDDL domain and its problem) through ``write_files_atomic``: they are written into a temp
folder beside the target and moved into place as one, so concurrent runs never leave a domain
from one run beside a problem from another.
"""

from __future__ import annotations

import contextlib
import ctypes
import enum
import errno
import os
import shutil
import stat
import sys
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

from rosreconf.errors import UsageError

STDOUT = "-"
"""The output name that means standard output."""


class TargetKind(enum.Enum):
    """What an output path is, and so how it may be written."""

    STDOUT = "stdout"
    STREAM = "stream"
    NEW = "new"
    FILE = "file"


@dataclass(frozen=True)
class OutputTarget:
    """An output path, checked: where the bytes go and which mode the file keeps.

    Attributes:
        shown: the path as the user gave it (for messages).
        kind: standard output, this process's own stdout/stderr by a path, a new file, or an
            existing regular file.
        path: the real path to write (symlinks followed); ``-`` for standard output.
        mode: the permission bits to give the file (the old file's, else 0666 minus umask).
        fd: for ``TargetKind.STREAM``, the descriptor (1 or 2) the bytes are written to.
    """

    shown: str
    kind: TargetKind
    path: Path
    mode: int
    fd: int | None = None

    @property
    def is_stdout(self) -> bool:
        """Tell whether the bytes go to standard output instead of a file."""
        return self.kind is TargetKind.STDOUT


def output_target(given: str | Path, *, stdout_ok: bool = True) -> OutputTarget:
    """Decide what ``given`` is and whether rosreconf may write it; see the module docstring.

    Raises:
        UsageError: the name is empty, or names a folder, a special file, a symlink loop, a
            path through a file, or a folder that does not exist.
    """
    shown = str(given)
    if shown == "":
        raise UsageError("-o '': the output file name is empty (give a file name, or - for stdout)")
    if shown == STDOUT:
        if not stdout_ok:
            raise UsageError("-o -: this output cannot go to stdout (give a file name)")
        return OutputTarget(shown, TargetKind.STDOUT, Path(STDOUT), 0)
    fd = own_stream(shown)
    if fd is not None:
        return OutputTarget(shown, TargetKind.STREAM, Path(shown), 0, fd)
    real = Path(os.path.realpath(shown))
    try:
        info = os.stat(real)
    except FileNotFoundError:
        if os.path.islink(real):
            raise UsageError(f"{shown}: is a symlink loop (point it at a real file)") from None
        parent = real.parent
        if not parent.is_dir():
            raise UsageError(f"{shown}: folder {parent} does not exist (create it first)") from None
        return OutputTarget(shown, TargetKind.NEW, real, 0o666 & ~_umask())
    except NotADirectoryError:
        raise UsageError(f"{shown}: a part of this path is a file, not a folder") from None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise UsageError(f"{shown}: is a symlink loop (point it at a real file)") from None
        raise UsageError(f"{shown}: cannot write: {exc.strerror or exc}") from None
    if stat.S_ISREG(info.st_mode):
        return OutputTarget(shown, TargetKind.FILE, real, stat.S_IMODE(info.st_mode))
    what = special_kind(info.st_mode)
    if stat.S_ISDIR(info.st_mode):
        raise UsageError(f"{shown}: is a folder, not a file (give a file name inside it)")
    raise UsageError(
        f"{shown}: is {what}; rosreconf replaces only regular files "
        "(give a regular file's name, or - to write to stdout)"
    )


STREAM_NAMES = {
    "/dev/stdout": 1, "/dev/fd/1": 1, "/proc/self/fd/1": 1,
    "/dev/stderr": 2, "/dev/fd/2": 2, "/proc/self/fd/2": 2,
}  # fmt: skip
"""The usual names of the process's own streams; a name decides between 1 and 2 when both
descriptors are one file (a terminal)."""


def own_stream(given: str) -> int | None:
    """Return 1 or 2 when ``given`` names this process's own stdout or stderr, else None.

    Decided by the file itself, not only by the name: any path to the same file (device and
    inode) as descriptor 1 or 2 counts, so ``/proc/self/fd/1``, a symlink to ``/dev/stdout``
    and ``-o log >> log`` are all recognised.
    """
    try:
        info = os.stat(given)
    except (OSError, ValueError):
        return None
    first = STREAM_NAMES.get(os.path.normpath(given), 1)
    for fd in (first, 3 - first):
        try:
            mine = os.fstat(fd)
        except OSError:
            continue
        if (mine.st_dev, mine.st_ino) == (info.st_dev, info.st_ino):
            return fd
    return None


def write_stream(target: OutputTarget, payload: bytes) -> None:
    """Write ``payload`` to the descriptor of a ``TargetKind.STREAM`` target, all of it.

    Python's own buffered stream on that descriptor is flushed first, so that what rosreconf
    printed before stays before.

    Raises:
        UsageError: the write failed (a closed pipe, a full disk).
    """
    fd = 2 if target.fd == 2 else 1
    with contextlib.suppress(OSError, ValueError, AttributeError):
        (sys.stdout if fd == 1 else sys.stderr).flush()
    view = memoryview(payload)
    try:
        while view:
            view = view[os.write(fd, view) :]
    except OSError as exc:
        raise UsageError(f"{target.shown}: cannot write: {exc.strerror or exc}") from None


def special_kind(mode: int) -> str:
    """Name a file type the way a user would ("a character device", "a FIFO")."""
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISSOCK(mode):
        return "a socket"
    if stat.S_ISREG(mode):
        return "a regular file"
    return "a special file"


def write_atomic(path: Path | str, data: bytes | str) -> Path:
    """Replace ``path`` by ``data`` in one step; leave ``path`` untouched on any failure.

    Text is written as UTF-8. ``path`` is checked by ``output_target`` (symlinks are written
    through, the old mode is kept, special files are refused); the real path is returned.
    A path that is this process's own stdout or stderr is written to that stream instead,
    appended, never replaced (see the module docstring).

    Raises:
        UsageError: ``path`` may not be written (see ``output_target``), or writing failed.
    """
    target = output_target(path, stdout_ok=False)
    payload = data.encode("utf-8") if isinstance(data, str) else data
    if target.kind is TargetKind.STREAM:
        write_stream(target, payload)
        return target.path
    real = target.path
    try:
        fd, tmp = tempfile.mkstemp(dir=real.parent, prefix=f".{real.name}.", suffix=".tmp")
    except OSError as exc:
        raise UsageError(f"{target.shown}: cannot write: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "wb") as out:
            out.write(payload)
            out.flush()
            os.fsync(out.fileno())
        os.chmod(tmp, target.mode)
        os.replace(tmp, real)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise UsageError(f"{target.shown}: cannot write: {exc.strerror or exc}") from None
        raise
    return real


def output_folder(given: str | Path) -> Path:
    """Check an output folder given with ``-o`` and create it (with parents) if it is new.

    Raises:
        UsageError: the name is empty or ``-``, names a file or special file, or the folder
            cannot be created.
    """
    shown = str(given)
    if shown == "":
        raise UsageError("-o '': the output folder name is empty (give a folder name)")
    if shown == STDOUT:
        raise UsageError("-o -: this command writes several files (give a folder name)")
    path = Path(shown)
    try:
        info = os.stat(path)
    except FileNotFoundError:
        info = None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise UsageError(f"{shown}: is a symlink loop (point it at a real folder)") from None
        if exc.errno == errno.ENOTDIR:
            raise UsageError(f"{shown}: a part of this path is a file, not a folder") from None
        raise UsageError(f"{shown}: cannot use as a folder: {exc.strerror or exc}") from None
    if info is not None and not stat.S_ISDIR(info.st_mode):
        raise UsageError(
            f"{shown}: is {special_kind(info.st_mode)}, not a folder (give a folder name)"
        )
    if info is None:
        try:
            path.mkdir(parents=True, exist_ok=True)
        except FileExistsError:
            raise UsageError(f"{shown}: a part of this path is a file, not a folder") from None
        except NotADirectoryError:
            raise UsageError(f"{shown}: a part of this path is a file, not a folder") from None
        except OSError as exc:
            raise UsageError(f"{shown}: cannot create folder: {exc.strerror or exc}") from None
    return path


def write_files_atomic(folder: Path, files: Mapping[str, bytes | str]) -> Path:
    """Put ``files`` (name -> content) into ``folder`` as one step; return the folder.

    The files are written into a temp folder beside ``folder``, which is then renamed into
    place (or, when ``folder`` already has content, swapped with it in one
    ``renameat2(RENAME_EXCHANGE)`` call on Linux). Entries of the old folder that are not
    among ``files`` are moved back into the new one: they are not ours to delete.

    Raises:
        UsageError: ``folder`` names a file or special file, or cannot be written.
    """
    parent = output_folder(folder.parent if str(folder.parent) else Path("."))
    target = Path(os.path.realpath(folder))
    with contextlib.suppress(FileNotFoundError):
        info = os.stat(target)
        if not stat.S_ISDIR(info.st_mode):
            raise UsageError(f"{folder}: is {special_kind(info.st_mode)}, not a folder")
    try:
        staging = Path(tempfile.mkdtemp(dir=parent, prefix=f".{target.name}.", suffix=".tmp"))
    except OSError as exc:
        raise UsageError(f"{folder}: cannot write: {exc.strerror or exc}") from None
    try:
        for name, data in files.items():
            payload = data.encode("utf-8") if isinstance(data, str) else data
            with open(staging / name, "wb") as out:
                out.write(payload)
                out.flush()
                os.fsync(out.fileno())
            os.chmod(staging / name, 0o666 & ~_umask())
        os.chmod(staging, 0o777 & ~_umask())
        try:
            os.rename(staging, target)  # new or empty folder: one rename
            return folder
        except OSError as exc:
            if exc.errno not in (errno.ENOTEMPTY, errno.EEXIST):
                raise
        _exchange(staging, target)  # staging now holds the old folder
        for entry in os.listdir(staging):
            if entry not in files:
                with contextlib.suppress(OSError):
                    os.rename(staging / entry, target / entry)
    except OSError as exc:
        raise UsageError(f"{folder}: cannot write: {exc.strerror or exc}") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return folder


RENAME_EXCHANGE = 2
"""``renameat2`` flag: swap two paths atomically (Linux 3.15+)."""


def _exchange(a: Path, b: Path) -> None:
    """Swap two folders in one step where the kernel can; else move ``b`` aside first."""
    if sys.platform.startswith("linux"):
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = getattr(libc, "renameat2", None)
        if renameat2 is not None:
            at_fdcwd = -100
            if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), RENAME_EXCHANGE) == 0:
                return
            code = ctypes.get_errno()
            if code not in (errno.ENOSYS, errno.EINVAL):
                raise OSError(code, os.strerror(code), str(b))
    aside = Path(tempfile.mkdtemp(dir=b.parent, prefix=f".{b.name}.", suffix=".old"))
    os.rename(b, aside / "old")
    os.rename(a, b)
    os.rename(aside / "old", a)
    aside.rmdir()


def _umask() -> int:
    """Return the process umask (reading it means setting it; set it straight back)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask
