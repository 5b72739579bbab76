"""The one way mechsing reads a user's file and the one way it writes one (a leaf module).

Reading, :func:`read_input`: a regular file, or a pipe or FIFO (``mechsing analyze
<(generate ...)``), read up to a size cap; anything else (a directory, a character or
block device such as ``/dev/zero``, a socket) is refused as "not a regular file" before
it is read.  A FIFO is opened without blocking and read with a timeout
(:data:`PIPE_WAIT_SECONDS` without data), so a FIFO nobody writes to is an error, not a
hang.

Writing, :func:`write_output` and :func:`open_output`: every file a command writes
(``-o OUT``, a report and its figures) is written into a uniquely named temporary file
created exclusively in the target's directory (never through a link planted there), then
renamed over the target in one step: a reader sees the old file or the whole new one, and
an error or an interrupt leaves the target as it was and no temporary file.  Before any
work, :func:`check_output` applies the rules every command shares:

* the output's directory must exist (mechsing creates no directories but a report's own
  figures folder);
* the output must not be a directory;
* the output must not be the same file as an input (compared by resolved path and by
  device and inode: a symbolic or hard link to the input is the input).

An output that names a symbolic link is written to the file the link points to.  An
output that exists and is not a regular file (``/dev/null``, ``/dev/stdout``, a FIFO)
is written to as a stream.  With ``follow_links=False`` (the files a command names itself,
such as ``exercise make``'s in its variant folders) no link is followed: whatever the
name holds (a symbolic link, a FIFO) is replaced by the new file, and what it pointed to
is left as it was.  Errors are :class:`~mechsing.errors.UserError` (exit 2)
whose message names the file.
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import select
import stat
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import IO

from mechsing.errors import InputError, UserError, raise_if_stopped

__all__ = [
    "PIPE_WAIT_SECONDS",
    "InputError",
    "check_output",
    "make_output_folder",
    "open_output",
    "read_input",
    "write_output",
]

#: longest wait for data from a pipe or FIFO (its first bytes, or the next ones), seconds
PIPE_WAIT_SECONDS = 30.0
_CHUNK = 1 << 16
#: the errors of writing a file (full disk, quota, size limit, device, read-only, access)
_WRITE_ERRORS = {
    errno.ENOSPC,
    errno.EDQUOT,
    errno.EFBIG,
    errno.EIO,
    errno.EROFS,
    errno.EACCES,
    errno.EPERM,
    errno.EXDEV,
    errno.EBUSY,
}

PathLike = str | os.PathLike[str]


# --------------------------------------------------------------------------- reading


def _kind(mode: int) -> str:
    """What a file that is not regular is, for messages."""
    if stat.S_ISDIR(mode):
        return "a directory"
    if stat.S_ISCHR(mode):
        return "a character device"
    if stat.S_ISBLK(mode):
        return "a block device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a special file"


def read_input(path: PathLike, limit: int, what: str = "file") -> bytes:
    """The bytes of the input ``path``: a regular file, a pipe or a FIFO of at most
    ``limit`` bytes (``what`` names the kind of file in the messages).

    Raises :class:`InputError` (bad input) for a path that does not exist or cannot be
    read, one that is not a regular file, pipe or FIFO, more than ``limit`` bytes, and a
    pipe or FIFO that gives no data for :data:`PIPE_WAIT_SECONDS`."""
    shown = os.fspath(path)
    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        raise InputError(shown, f"cannot read the file ({exc.strerror}); check the path") from None
    if not (stat.S_ISREG(mode) or stat.S_ISFIFO(mode)):
        raise InputError(shown, f"not a regular file ({_kind(mode)}); give the path of a {what}")
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        raise InputError(shown, f"cannot read the file ({exc.strerror})") from None
    try:
        mode = os.fstat(fd).st_mode  # what was opened, should the path have changed since
        if stat.S_ISREG(mode):
            os.set_blocking(fd, True)
            data = _read_regular(fd, limit, shown, what)
        elif stat.S_ISFIFO(mode):
            data = _read_pipe(fd, limit, shown, what)
        else:
            raise InputError(
                shown, f"not a regular file ({_kind(mode)}); give the path of a {what}"
            )
    except OSError as exc:
        raise InputError(shown, f"cannot read the file ({exc.strerror})") from None
    finally:
        os.close(fd)
    return data


def _too_large(shown: str, limit: int, what: str) -> InputError:
    return InputError(
        shown,
        f"more than {limit:,} bytes, more than a {what} may have",
    )


def _read_regular(fd: int, limit: int, shown: str, what: str) -> bytes:
    if os.fstat(fd).st_size > limit:
        raise _too_large(shown, limit, what)
    parts, total = [], 0
    while True:  # a file that grows while it is read stops at the cap too
        chunk = os.read(fd, min(_CHUNK, limit + 1 - total))
        if not chunk:
            return b"".join(parts)
        parts.append(chunk)
        total += len(chunk)
        if total > limit:
            raise _too_large(shown, limit, what)


def _read_pipe(fd: int, limit: int, shown: str, what: str) -> bytes:
    """A pipe or FIFO opened without blocking: read until its writers close it, waiting at
    most PIPE_WAIT_SECONDS for each piece.  (A FIFO nobody has opened for writing reads as
    empty without blocking; poll() reports it only once a writer has come.)"""
    poller = select.poll()
    poller.register(fd, select.POLLIN)
    parts, total = [], 0
    while True:
        if not poller.poll(int(PIPE_WAIT_SECONDS * 1000)):
            raise InputError(
                shown,
                f"no data arrived for {PIPE_WAIT_SECONDS:g} s: a pipe or FIFO that no "
                f"program writes to? Write the {what} to a regular file and give its path",
            )
        try:
            chunk = os.read(fd, min(_CHUNK, limit + 1 - total))
        except BlockingIOError:
            continue
        if not chunk:
            return b"".join(parts)
        parts.append(chunk)
        total += len(chunk)
        if total > limit:
            raise _too_large(shown, limit, what)


# --------------------------------------------------------------------------- writing


def _identity(path: PathLike, follow: bool = True) -> tuple[str, tuple[int, int] | None]:
    """A file's resolved path and (device, inode) when it exists (without ``follow``, of
    the name itself: a symbolic link is not followed, its directory is resolved)."""
    if follow:
        real = os.path.realpath(path)
    else:
        head, tail = os.path.split(os.fspath(path))
        real = os.path.join(os.path.realpath(head or "."), tail)
    try:  # the path itself: the kernel follows /dev/stdout to a pipe realpath cannot name
        st = os.stat(path, follow_symlinks=follow)
    except OSError:
        return real, None
    return real, (st.st_dev, st.st_ino)


def check_output(
    path: PathLike,
    inputs: Iterable[PathLike] = (),
    option: str = "-o",
    follow_links: bool = True,
) -> Path:
    """The file to write for the output ``path`` (a symbolic link resolved, unless
    ``follow_links`` is false), after the rules every output follows: its directory
    exists, it is not a directory, and it is not the same file as any of ``inputs``.
    ``option`` names it in messages (``-o``)."""
    shown = os.fspath(path)
    real, ident = _identity(path, follow_links)
    if ident is None and not os.path.isdir(os.path.dirname(real)):
        # named as given, or where the link points
        missing = os.path.dirname(real if os.path.islink(shown) else shown)
        raise UserError(
            f"{option} {shown}: the directory {missing} does not exist; create it first "
            "(mechsing creates no directories) or choose another path"
        )
    if os.path.isdir(path) and (follow_links or not os.path.islink(path)):
        raise UserError(
            f"{option} {shown}: is a directory; name a file in it (e.g. {os.path.join(shown, 'out')})"
        )
    for given in inputs:
        in_real, in_ident = _identity(given)
        if in_real == real or (ident is not None and in_ident == ident):
            raise UserError(
                f"{option} {shown}: is the input file {os.fspath(given)} (the same file); "
                "writing there would replace it; choose another output path"
            )
    return Path(real)


def make_output_folder(
    folder: PathLike, inputs: Iterable[PathLike] = (), option: str = "-o"
) -> Path:
    """The folder an output's parts go in (a Markdown report's figures): created when
    missing (its parent must exist, as for every output); an existing one must be a
    directory that is none of ``inputs``."""
    shown = os.fspath(folder)
    real, _ = _identity(folder)
    for given in inputs:
        if _identity(given)[0] == real:
            raise UserError(
                f"{option}: the folder {shown} is the input {os.fspath(given)}; "
                "choose another output path"
            )
    parent = os.path.dirname(real) or "."
    if not os.path.isdir(parent):
        raise UserError(
            f"{option}: the directory {parent} does not exist; create it first "
            "(mechsing creates no directories) or choose another path"
        )
    try:
        os.mkdir(real)
    except FileExistsError:
        if not os.path.isdir(real):
            raise UserError(
                f"{option}: {shown} exists and is not a directory; mechsing writes the "
                "figures there: move it or choose another output path"
            ) from None
    except OSError as exc:
        raise UserError(
            f"{option}: cannot create the folder {shown} ({exc.strerror}); choose a writable path"
        ) from None
    return Path(real)


def _cannot(option: str, shown: str, exc: OSError) -> UserError:
    return UserError(
        f"{option} {shown}: cannot write it ({exc.strerror or exc}); choose a writable path"
    )


def _temporary(target: Path, follow: bool = True) -> tuple[int, Path]:
    """A new, uniquely named file beside ``target``, created exclusively (a name that
    exists, a link included, is never opened), with the target's permissions when it
    exists and the usual ones (0666 less the umask) when not."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
    flags |= getattr(os, "O_CLOEXEC", 0)
    for _ in range(100):
        tmp = target.with_name(f".{target.name}.{secrets.token_hex(6)}.partial")
        try:
            fd = os.open(tmp, flags, 0o666)
        except FileExistsError:
            continue
        with contextlib.suppress(OSError):
            st = os.stat(target, follow_symlinks=follow)
            if stat.S_ISREG(st.st_mode):
                os.fchmod(fd, stat.S_IMODE(st.st_mode))
        return fd, tmp
    raise FileExistsError(errno.EEXIST, "no free temporary name", str(target))  # pragma: no cover


@contextlib.contextmanager
def open_output(
    path: PathLike,
    inputs: Iterable[PathLike] = (),
    binary: bool = False,
    option: str = "-o",
    follow_links: bool = True,
) -> Iterator[IO]:
    """A file object to write the output ``path`` through (text in UTF-8, or ``binary``):
    a temporary file beside it, renamed over ``path`` when the block ends normally and
    removed when it raises (an interrupt included), so ``path`` is never half written; nor
    is it replaced once a signal asked the command to stop
    (:func:`~mechsing.errors.raise_if_stopped`).
    The rules of :func:`check_output` apply; without ``follow_links``, whatever ``path``
    names (a link included) is replaced."""
    shown = os.fspath(path)
    target = check_output(path, inputs, option, follow_links)
    try:
        st = os.stat(path)
    except OSError:
        st = None
    if follow_links and st is not None and not stat.S_ISREG(st.st_mode):
        with _stream(Path(path), shown, binary, option) as f:
            yield f
        return
    try:
        fd, tmp = _temporary(target, follow_links)
    except OSError as exc:
        raise _cannot(option, shown, exc) from None
    try:
        with os.fdopen(fd, "wb") if binary else _text(fd) as f:
            yield f
            f.flush()
            os.fsync(f.fileno())
        raise_if_stopped()  # a stop some code swallowed: the old output stays
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and exc.errno in _WRITE_ERRORS:
            raise _cannot(option, shown, exc) from None
        raise


def _text(fd: int) -> IO[str]:
    return open(fd, "w", encoding="utf-8", newline="")  # noqa: SIM115 - closed by the caller


@contextlib.contextmanager
def _stream(target: Path, shown: str, binary: bool, option: str) -> Iterator[IO]:
    """An existing output that is not a regular file (/dev/null, a FIFO...): written as a
    stream; a FIFO nobody reads is an error, not a hang."""
    try:
        fd = os.open(target, os.O_WRONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as exc:
        if exc.errno == errno.ENXIO:
            raise UserError(
                f"{option} {shown}: a FIFO that no program reads; start the reader first or "
                "write to a regular file"
            ) from None
        raise _cannot(option, shown, exc) from None
    os.set_blocking(fd, True)
    with os.fdopen(fd, "wb") if binary else _text(fd) as f:
        yield f


def write_output(
    path: PathLike,
    data: str | bytes,
    inputs: Iterable[PathLike] = (),
    option: str = "-o",
    follow_links: bool = True,
) -> Path:
    """Write ``data`` (text in UTF-8, or bytes) to the output ``path`` atomically (see
    :func:`open_output`); the file written (a symbolic link resolved, unless
    ``follow_links`` is false)."""
    binary = isinstance(data, bytes)
    with open_output(path, inputs, binary, option, follow_links) as f:
        f.write(data)
    return Path(_identity(path, follow_links)[0])
