"""The user's files, read and written safely.

A case file must be a regular file of bounded size: reading a FIFO blocks until a
writer comes, and ``/dev/zero`` or ``/dev/urandom`` never end. What mdcalc writes
(``--save``, ``--plot``, ``new -o``, ``run --out``, ``sweep --out``) goes through a
temporary file in the same folder and a rename, so a reader never sees half a file;
without ``--force`` the file is created exclusively (two runs at once cannot both
think they made it); with it, only a regular file is replaced (never a device node,
a FIFO or a folder), and it keeps its mode; a new file gets the umask's mode.
"""

from __future__ import annotations

import os
import stat
import tempfile
from collections.abc import Callable, Iterable
from pathlib import Path

from mdcalc.errors import InputError, Problem

#: The largest case file read. The biggest shipped case is about 4 kB; a tabulated
#: torque of a few thousand rows stays far below this.
MAX_CASE_BYTES = 4 * 1024 * 1024


def read_regular(path: Path, limit: int = MAX_CASE_BYTES) -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them; InputError
    for anything else (missing, a folder, a FIFO, a device, too large, unreadable)."""
    try:
        # O_NONBLOCK: opening a FIFO for reading must not wait for a writer.
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0))
    except FileNotFoundError:
        raise InputError(path, [Problem("no such file")]) from None
    except IsADirectoryError:
        raise InputError(path, [Problem("is a directory, not a case file")]) from None
    except OSError as exc:
        raise InputError(path, [Problem(f"cannot read: {exc.strerror}")]) from None
    status = os.fstat(fd)
    mode, size = status.st_mode, status.st_size
    if not stat.S_ISREG(mode):
        os.close(fd)
        if stat.S_ISDIR(mode):
            raise InputError(path, [Problem("is a directory, not a case file")])
        raise InputError(path, [Problem(f"is {_kind(mode)}, not a regular case file")])
    try:
        data = _read_fd(fd, min(size, limit) + 1, limit + 1)
    except OSError as exc:
        raise InputError(path, [Problem(f"cannot read: {exc.strerror}")]) from None
    finally:
        os.close(fd)
    if len(data) > limit:
        raise InputError(
            path, [Problem(f"is larger than {limit // (1024 * 1024)} MiB; a case file is small")]
        )
    return data


def _read_fd(fd: int, hint: int, most: int) -> bytes:
    """Up to ``most`` bytes from ``fd``, asking for ``hint`` first (the size fstat
    gave, plus one): a buffer of the file's size, not of the 4 MiB limit (allocating
    that cost 25 µs a file in a batch). The file may grow while it is read."""
    chunks = [os.read(fd, hint)]
    got = len(chunks[0])
    while chunks[-1] and got < most:
        chunks.append(os.read(fd, min(most - got, 1 << 20)))
        got += len(chunks[-1])
    return b"".join(chunks)[:most]


def write_atomic(
    path: Path,
    content: str | bytes | bytearray | Iterable[bytes | memoryview] | Callable[[str], None],
    *,
    replace: bool,
    option: str = "",
) -> None:
    """Write ``content`` to ``path`` (text, bytes, byte pieces, or a function
    that writes the file whose name it is given) through a temporary file and a
    rename. ``replace`` False: the file must not exist (created exclusively); True: an
    existing regular file is replaced and keeps its mode. Missing folders under
    ``path`` are made. ``option`` (``"--plot: "``) starts each message."""
    existing = _existing_mode(path, option)
    if existing is not None and not replace:
        raise InputError(path, [Problem(f"{option}file exists; use --force to overwrite it")])
    directory = path.parent if str(path.parent) else Path(".")
    try:
        directory.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=directory)
    except OSError as exc:
        raise InputError(path, [Problem(f"{option}cannot write: {exc.strerror}")]) from None
    try:
        if callable(content):
            os.close(fd)
            content(tmp)
        else:
            with os.fdopen(fd, "wb") as handle:
                if isinstance(content, str):
                    handle.write(content.encode("utf-8"))
                elif isinstance(content, bytes | bytearray):
                    handle.write(content)
                else:  # pieces, written one after another as they come
                    handle.writelines(content)
        os.chmod(tmp, existing if existing is not None else 0o666 & ~_umask())
        if replace:
            os.replace(tmp, path)
        else:
            _create(tmp, path, option)
    finally:
        Path(tmp).unlink(missing_ok=True)


def _existing_mode(path: Path, option: str) -> int | None:
    """The permission bits of the regular file at ``path``; None if there is none;
    InputError for anything that is not a regular file."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return None
    except OSError as exc:
        raise InputError(path, [Problem(f"{option}cannot use this path: {exc.strerror}")]) from None
    if stat.S_ISDIR(mode):
        raise InputError(path, [Problem(f"{option}is a folder; give a file name")])
    if not stat.S_ISREG(mode):
        raise InputError(
            path, [Problem(f"{option}is {_kind(mode)}; only a regular file is ever replaced")]
        )
    return stat.S_IMODE(mode)


def _create(tmp: str, path: Path, option: str) -> None:
    """Put the finished ``tmp`` at ``path`` only if nothing is there: a hard link
    fails on an existing name, atomically; where links are not supported, an
    exclusive create reserves the name first."""
    try:
        os.link(tmp, path)
        return
    except FileExistsError:
        raise InputError(
            path, [Problem(f"{option}file exists (just made by another run); use --force")]
        ) from None
    except OSError:
        pass  # no hard links on this file system
    try:
        os.close(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
    except FileExistsError:
        raise InputError(
            path, [Problem(f"{option}file exists (just made by another run); use --force")]
        ) from None
    os.replace(tmp, path)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _kind(mode: int) -> str:
    if stat.S_ISFIFO(mode):
        return "a FIFO (named pipe)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"
