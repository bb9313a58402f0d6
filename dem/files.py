"""Where outputs go: every file dem writes (log, dumps, restarts, write_data, print and series files, the
shape database) is a regular file. An existing name that is anything else (a device such as /dev/null, a
FIFO, a socket, a folder, or a symbolic link to one) is refused: a temporary file renamed over it would
replace it (run as root, even /dev/null), and a FIFO would block the run until a reader comes."""
import errno
import os
import stat

from .errors import DemError

_KINDS = ((stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO"),
          (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a folder"))


def check_target(path, use):
    """DemError naming `use` and `path` when `path` exists and is not a regular file (links followed)."""
    try:
        mode = os.stat(path).st_mode
    except OSError:          # nothing there yet (or a dangling link): the file is created
        return
    if stat.S_ISREG(mode):
        return
    kind = next((name for test, name in _KINDS if test(mode)), "not a regular file")
    link = " (through a symbolic link)" if os.path.islink(path) else ""
    raise DemError(f"{use}: '{path}' is {kind}{link}: dem writes its outputs to regular files only")


def ensure_dir(path):
    """Create the folder of `path` when missing."""
    folder = os.path.dirname(path)
    if folder:
        try:
            os.makedirs(folder, exist_ok=True)
        except FileExistsError:     # a file where a folder should be: say so (its errno says "File exists")
            raise NotADirectoryError(errno.ENOTDIR, f"'{folder}' is not a folder") from None


def open_output(path, use, mode="w"):
    """`path` opened to write in `mode` (text modes in UTF-8), its folder created; a DemError naming `use`
    when it is not a regular file or cannot be opened."""
    check_target(path, use)
    try:
        ensure_dir(path)
        return open(path, mode, **({} if "b" in mode else {"encoding": "utf-8"}))
    except OSError as e:
        raise DemError(f"{use}: cannot write '{path}': {e.strerror or e}") from None


def replace_file(path, write, use):
    """Write `path` through a temporary file that `write(temporary path)` fills and that is then renamed over
    it: a reader (or a crash, or an interrupt) never sees half a file, and no temporary file stays behind.
    A symbolic link is kept: the file it names is replaced."""
    check_target(path, use)
    target = os.path.realpath(path)
    folder, base = os.path.split(target)
    tmp = os.path.join(folder, f".{base}.{os.getpid()}.tmp")
    try:
        write(tmp)
        os.replace(tmp, target)
    except BaseException as e:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        if isinstance(e, OSError):
            raise DemError(f"{use}: cannot write '{path}': {e.strerror or e}") from None
        raise


def atomic_write(path, data, use):
    """`replace_file` with `data` (str, written as UTF-8, or bytes), the folder created when missing."""
    if isinstance(data, str):
        data = data.encode("utf-8")
    try:
        ensure_dir(path)
    except OSError as e:
        raise DemError(f"{use}: cannot write '{path}': {e.strerror or e}") from None

    def write(tmp):
        with open(tmp, "wb") as fh:
            fh.write(data)
    replace_file(path, write, use)
