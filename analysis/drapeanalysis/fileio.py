"""How the analysis opens its inputs and writes its outputs, by drapelab's rules (README, exit
status): an input must be a regular file, and an output appears whole or not at all.

A named pipe where a file is expected would block its reader until some writer opened it (for
ever, in practice), and a device may never end; drapelab refuses both as "not a regular file"
(core/io/json_reader.cpp, unreadable_file_reason), and so does open_input, with the same
words. An output is written to a temporary file beside its place and renamed into it when
complete (atomic_output), so a full disk, a quota or a file size limit leaves the old file or
none, never a half one that looks finished."""
import contextlib
import os
import stat
from pathlib import Path


class OutputError(Exception):
    """An output could not be written (exit status 4); the message names the file and why."""


def input_problem(path):
    """Why `path` cannot be read as an input file, in drapelab's words, or None when it can."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return "no such file"
    except OSError as e:  # a path through a file, a loop of links: the system's own words
        return e.strerror or str(e)
    if stat.S_ISDIR(mode):
        return "is a directory, not a file"
    if not stat.S_ISREG(mode):
        return "not a regular file"
    return None


def open_input(path, mode="r"):
    """`path` opened for reading (mode "r": UTF-8 text, or "rb"); a ValueError naming it when it
    is not a regular file or cannot be opened (exit status 2 in the report)."""
    problem = input_problem(path)
    if problem:
        raise ValueError(f"{path}: {problem}")
    try:
        # Non-blocking: had the file been replaced by a pipe since the stat, the open would wait
        # for a writer; this way it returns, and fstat refuses it.
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as e:
        raise ValueError(f"{path}: cannot open file ({e.strerror or e})") from e
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise ValueError(f"{path}: not a regular file")
    os.set_blocking(fd, True)
    return os.fdopen(fd, mode, **({} if "b" in mode else {"encoding": "utf-8"}))


@contextlib.contextmanager
def atomic_output(path):
    """Yields the temporary path to write all of `path` to, beside it (the same file system, so
    the rename is atomic); renames it to `path` when the block ends. When the block raises, the
    temporary is removed; an OSError (a full disk, no permission, a file size limit) becomes an
    OutputError naming `path`."""
    path = Path(path)
    # The suffix stays last: matplotlib and ffmpeg choose the format by it.
    temporary = path.with_name(f".{path.stem}.tmp-{os.getpid()}{path.suffix}")
    try:
        yield temporary
        os.replace(temporary, path)
    except BaseException as e:
        with contextlib.suppress(OSError):
            temporary.unlink()
        if isinstance(e, OSError):
            raise OutputError(f"cannot write {path}: {e.strerror or e}") from e
        raise


def output_folder(path):
    """Creates the folder `path` (its parent exists) unless it is there. A file in its place is a
    ValueError (bad input, exit status 2), a folder that cannot be created an OutputError."""
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"{path}: not a folder (the report writes its files there)")
    try:
        path.mkdir(exist_ok=True)
    except OSError as e:
        raise OutputError(f"cannot create folder {path}: {e.strerror or e}") from e
    return path


def check_writable_folder(path):
    """A ValueError (bad input, exit status 2) naming the existing folder `path` when a file
    cannot be created in it: tried by creating a probe and removing it, as permissions do not
    tell everything (root, read-only mounts). Checked before any work, a folder the report
    cannot write into is named up front, not found by the first write after the figures."""
    probe = Path(path) / f".drapelab-write-probe-{os.getpid()}"
    try:
        probe.touch(exist_ok=False)
    except OSError as e:
        raise ValueError(f"{path}: cannot be written ({e.strerror or e}): the report writes "
                         "its files there") from e
    probe.unlink()
