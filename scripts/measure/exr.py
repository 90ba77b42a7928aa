"""Mean R, G, B of an OpenEXR image, standard library only.

Reads single-part scanline files with 32-bit float or 16-bit half channels and the
compressions NONE, ZIPS and ZIP (OpenEXR file layout, "Technical Introduction to OpenEXR",
§Scan Lines; ZIP: zlib, then a byte predictor and the two-half interleave undone). That
covers Iris's, Mitsuba's and LuxCore's EXR output; other files give None."""
import struct
import zlib

NONE, ZIPS, ZIP = 0, 2, 3
LINES_PER_BLOCK = {NONE: 1, ZIPS: 1, ZIP: 16}


def _header(data):
    """(attributes {name: (type, bytes)}, offset just past the header)."""
    i, attrs = 8, {}
    while data[i] != 0:
        n = data.index(b"\0", i)
        t = data.index(b"\0", n + 1)
        size = struct.unpack_from("<i", data, t + 1)[0]
        attrs[data[i:n].decode()] = (data[n + 1:t].decode(), data[t + 5:t + 5 + size])
        i = t + 5 + size
    return attrs, i + 1


def _channels(raw):
    """[(name, pixel type)] in file order (alphabetical): 1 = half, 2 = float."""
    out, i = [], 0
    while raw[i] != 0:
        n = raw.index(b"\0", i)
        out.append((raw[i:n].decode(), struct.unpack_from("<i", raw, n + 1)[0]))
        i = n + 1 + 16
    return out


def _unzip(block):
    """OpenEXR ZIP/ZIPS block: zlib, predictor (t[i] = t[i−1] + t[i] − 128), interleave."""
    t = bytearray(zlib.decompress(block))
    for i in range(1, len(t)):
        t[i] = (t[i - 1] + t[i] - 128) & 0xFF
    half = (len(t) + 1) // 2
    out = bytearray(len(t))
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return bytes(out)


def mean_rgb(path):
    """[mean R, mean G, mean B] over all pixels, or None for a file this reader does not handle."""
    try:
        data = open(path, "rb").read()
    except OSError:
        return None
    if len(data) < 8 or struct.unpack_from("<I", data, 0)[0] != 20000630 or data[5] & 0x1E:
        return None  # not EXR, or tiled / long names / deep / multi-part
    attrs, pos = _header(data)
    comp = attrs["compression"][1][0]
    if comp not in LINES_PER_BLOCK:
        return None
    chans = _channels(attrs["channels"][1])
    if any(pt not in (1, 2) for _, pt in chans):
        return None
    x0, y0, x1, y1 = struct.unpack("<iiii", attrs["dataWindow"][1])
    width, height = x1 - x0 + 1, y1 - y0 + 1
    nblocks = -(-height // LINES_PER_BLOCK[comp])
    offsets = struct.unpack_from(f"<{nblocks}Q", data, pos)
    sums = {name: 0.0 for name, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", data, off)
        block = data[off + 8:off + 8 + size]
        lines = min(LINES_PER_BLOCK[comp], y1 - y + 1)
        expected = lines * width * sum(2 if pt == 1 else 4 for _, pt in chans)
        if comp != NONE and size < expected:
            block = _unzip(block)
        i = 0
        for _ in range(lines):
            for name, pt in chans:
                fmt = f"<{width}{'e' if pt == 1 else 'f'}"
                sums[name] += sum(struct.unpack_from(fmt, block, i))
                i += struct.calcsize(fmt)
    n = width * height
    if not all(c in sums for c in "RGB"):
        return None
    return [sums[c] / n for c in "RGB"]
