"""Files dem writes with HDF5 and reads back (restarts, the shape database), checked whole before HDF5 sees
them. The HDF5 library trusts its input: a damaged file can make it raise odd errors, loop for ever
(deaf to SIGTERM) or crash the process. So each such file starts with a 512-byte header, written in the
HDF5 user block (which HDF5 skips: h5py, h5dump and ParaView open the file as any HDF5 file), that gives
the kind of file, the length of the HDF5 content after the header and its SHA-256:

    dem checked file 1\\n
    kind restart\\n
    length 97408\\n
    sha256 9f86d0...\\n
    (zero bytes up to 512)

`check` reads the file in Python, in chunks (a restart can be gigabytes: never whole in memory), and
returns what is wrong with it, or None; only then may h5py open it. Under MPI the caller checks on one
rank and broadcasts the verdict (a whole-file read on every rank would not scale). Layout:
docs/restart.md."""
import hashlib
import os
from contextlib import contextmanager

HEADER_SIZE = 512                 # the HDF5 user block: a power of two, at least 512
MAGIC = b"dem checked file 1\n"
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
CHUNK = 1 << 22
LABELS = {"restart": "dem restart file", "shapes": "dem shape database"}

# reasons returned by `check`
UNREADABLE = "unreadable"   # cannot be opened or read (a permission, an I/O error)
EMPTY = "empty"             # zero bytes
PLAIN_HDF5 = "hdf5"         # an HDF5 file without the header: written by an older dem, or not by dem
FOREIGN = "foreign"         # anything else that is not ours (a text, a pickle, another kind of dem file)
DAMAGED = "damaged"         # ours, but truncated or changed since it was written


def header(kind, length, digest):
    text = MAGIC + b"kind %s\nlength %d\nsha256 %s\n" % (kind.encode(), length, digest.encode())
    return text + bytes(HEADER_SIZE - len(text))


def _digest(fh, length):
    """SHA-256 of the next `length` bytes of `fh` (fewer if the file ends first) and how many were read."""
    h, done = hashlib.sha256(), 0
    while done < length:
        block = fh.read(min(CHUNK, length - done))
        if not block:
            break
        h.update(block)
        done += len(block)
    return h.hexdigest(), done


def seal(path, kind):
    """Write the header of the HDF5 file `path` (made with a user block of HEADER_SIZE bytes, closed):
    the checksum of everything after the header."""
    with open(path, "r+b") as fh:
        size = os.fstat(fh.fileno()).st_size
        fh.seek(HEADER_SIZE)
        digest, _ = _digest(fh, size - HEADER_SIZE)
        fh.seek(0)
        fh.write(header(kind, size - HEADER_SIZE, digest))


@contextmanager
def hdf5_writer(path, kind):
    """An h5py.File to fill, created at `path` with room for the header, sealed once closed."""
    import h5py
    with h5py.File(path, "w", userblock_size=HEADER_SIZE) as f:
        yield f
    seal(path, kind)


def _parse(head, kind):
    """(length, sha256) of a header, or (reason, text) of what is wrong with it."""
    unreadable = (DAMAGED, "is damaged: its checksum header is unreadable")
    text, _, padding = head.partition(b"\0")
    if any(padding):
        return DAMAGED, "is damaged: its checksum header holds stray bytes"
    try:
        lines = text.decode("ascii").split("\n")
    except UnicodeDecodeError:
        return unreadable
    fields = dict(line.split(" ", 1) for line in lines[1:-1] if " " in line)
    if lines[-1] != "" or len(lines) != 5 or list(fields) != ["kind", "length", "sha256"]:
        return unreadable
    if fields["kind"] != kind:
        if fields["kind"] in LABELS:
            return FOREIGN, f"is a {LABELS[fields['kind']]}, not a {LABELS[kind]}"
        return unreadable
    digest, length = fields["sha256"], fields["length"]
    if not (length.isdigit() and len(digest) == 64 and all(c in "0123456789abcdef" for c in digest)):
        return unreadable
    return int(length), digest


def check(path, kind):
    """None when `path` is a whole, unchanged file of `kind` (a key of LABELS), else (reason, text): one of
    the reasons above and what is wrong, a predicate to follow the file's name ("is damaged: ..."). Never
    raises (under MPI, rank 0 broadcasts the verdict and must reach the broadcast)."""
    try:
        with open(path, "rb") as fh:
            size = os.fstat(fh.fileno()).st_size
            head = fh.read(HEADER_SIZE)
            if not head:
                return EMPTY, "is empty (0 bytes): damaged or never written"
            if not head.startswith(MAGIC):
                return _not_sealed(fh, head, kind)
            if len(head) < HEADER_SIZE:
                return DAMAGED, f"is truncated: {size} bytes, less than its {HEADER_SIZE}-byte header"
            parsed = _parse(head, kind)
            if parsed[0] in (DAMAGED, FOREIGN):
                return parsed
            length, digest = parsed
            if size < HEADER_SIZE + length:
                return DAMAGED, (f"is truncated: {size} bytes where its header says {HEADER_SIZE + length} "
                                 f"(damaged, or not completely copied)")
            if size > HEADER_SIZE + length:
                return DAMAGED, f"is damaged: {size - HEADER_SIZE - length} bytes more than its header says"
            found, _ = _digest(fh, length)
            if found != digest:
                return DAMAGED, "is damaged: checksum mismatch (bytes changed after it was written)"
            return None
    except OSError as e:
        return UNREADABLE, f"cannot be opened: {e.strerror or e}"


def _not_sealed(fh, head, kind):
    if head.startswith(HDF5_SIGNATURE):
        return PLAIN_HDF5, (f"is an HDF5 file without dem's checksum header (a {LABELS[kind]} written by an "
                            f"older dem, or not a dem file)")
    fh.seek(HEADER_SIZE)
    if fh.read(len(HDF5_SIGNATURE)) == HDF5_SIGNATURE or (len(head) < len(MAGIC) and MAGIC.startswith(head)):
        return DAMAGED, "is damaged: its checksum header is unreadable"     # ours, its first bytes changed
    return FOREIGN, f"is not a {LABELS[kind]}"
