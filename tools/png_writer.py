"""A PNG writer for the procedural textures in scenes/data (standard library
only: zlib + struct), shared by tools/make-*.py."""
import struct
import zlib


def png(width, height, rows, channels=4):
    """PNG bytes of `rows` (height lists of width * channels bytes, top row
    first); channels 3 (RGB) or 4 (RGBA), 8 bits each."""
    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    colour_type = {3: 2, 4: 6}[channels]
    raw = b"".join(b"\x00" + bytes(row) for row in rows)
    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
