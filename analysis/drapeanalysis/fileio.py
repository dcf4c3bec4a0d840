"""How the analysis opens its inputs, by drapelab's rules (README, exit status): an input must
be a regular file.

A named pipe where a file is expected would block its reader until some writer opened it (for
ever, in practice), and a device may never end; drapelab refuses both as "not a regular file"
(core/scene/json_reader.cpp, unreadable_file_reason), and so does open_input, with the same
words."""
import os
import stat


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
