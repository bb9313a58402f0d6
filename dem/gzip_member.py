"""One gzip member grown snapshot by snapshot and complete after each: the readers that stop at the end of
the first member (OVITO among them) see every snapshot, and a file read while the run goes on is a valid
gzip file.

Each piece of text is deflated and sync-flushed (the deflate stream then ends on a byte boundary), then
closed with an empty final block and the gzip trailer (CRC-32, size). The next piece first cuts those
TAIL bytes off the file and continues the same deflate stream."""
import struct
import zlib

HEADER = b"\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\xff"   # gzip, deflate, no name, no time, unknown OS
FINAL_BLOCK = b"\x03\x00"                              # an empty fixed-Huffman block marked final
TAIL = len(FINAL_BLOCK) + 8                            # and the trailer: CRC-32 and size, 4 bytes each


class GzipMember:
    def __init__(self, level=6):
        self.level = level
        self.file_size = None     # the file's size after the last piece: None before the first
        self._start()

    def _start(self):
        self.deflate = zlib.compressobj(self.level, zlib.DEFLATED, -zlib.MAX_WBITS)   # raw deflate
        self.crc = 0
        self.size = 0

    def append(self, f, data):
        """Add `data` to the member in `f` (a file opened "r+b" or "ab" at its end; a new member starts
        when f is not where the last piece left the file, e.g. someone else wrote to it)."""
        end = f.seek(0, 2)
        continuing = self.file_size is not None and end == self.file_size
        if continuing:
            f.truncate(end - TAIL)
            f.seek(end - TAIL)
        else:
            self._start()
            f.write(HEADER)
        body = self.deflate.compress(data) + self.deflate.flush(zlib.Z_SYNC_FLUSH)
        self.crc = zlib.crc32(data, self.crc)
        self.size += len(data)
        f.write(body + FINAL_BLOCK + struct.pack("<II", self.crc, self.size & 0xFFFFFFFF))
        self.file_size = f.tell()
