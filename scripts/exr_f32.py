#!/usr/bin/env python3
"""Reads the RGB channels of a stagelight EXR (scan lines, f32 channels, ZIP or no
compression) into a float64 numpy array of shape (height, width, 3), without OpenEXR or
Mitsuba. Only what stagelight writes is supported."""
import struct
import zlib

import numpy as np

_COMPRESSION_LINES = {0: 1, 2: 1, 3: 16}  # none, ZIPS, ZIP


def _header(buf):
    if buf[:4] != b"\x76\x2f\x31\x01":
        raise ValueError("not an OpenEXR file")
    pos, attrs = 8, {}
    while buf[pos] != 0:
        end = buf.index(b"\0", pos)
        name = buf[pos:end].decode()
        tend = buf.index(b"\0", end + 1)
        kind = buf[end + 1:tend].decode()
        (size,) = struct.unpack_from("<i", buf, tend + 1)
        attrs[name] = (kind, buf[tend + 5:tend + 5 + size])
        pos = tend + 5 + size
    return attrs, pos + 1


def _channels(raw):
    out, pos = [], 0
    while raw[pos] != 0:
        end = raw.index(b"\0", pos)
        (ptype,) = struct.unpack_from("<i", raw, end + 1)
        out.append((raw[pos:end].decode(), ptype))
        pos = end + 1 + 16
    return out


def _unzip(data, expected):
    t = np.frombuffer(zlib.decompress(data), dtype=np.uint8).astype(np.int64)
    if len(t) != expected:
        raise ValueError("bad chunk size")
    t = (np.cumsum(np.concatenate([t[:1], t[1:] - 128])) & 0xFF).astype(np.uint8)
    half = (len(t) + 1) // 2
    out = np.empty_like(t)
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out.tobytes()


def load_rgb(path):
    buf = open(path, "rb").read()
    attrs, pos = _header(buf)
    xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"][1])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = attrs["compression"][1][0]
    lines = _COMPRESSION_LINES[comp]
    chans = _channels(attrs["channels"][1])
    sizes = [2 if t == 1 else 4 for _, t in chans]
    nchunks = (h + lines - 1) // lines
    offsets = struct.unpack_from("<%dQ" % nchunks, buf, pos)
    img = {name: np.zeros((h, w)) for name, _ in chans}
    for off in offsets:
        y, size = struct.unpack_from("<ii", buf, off)
        n = min(lines, ymax + 1 - y)
        data = buf[off + 8:off + 8 + size]
        expected = n * w * sum(sizes)
        if comp != 0 and size < expected:
            data = _unzip(data, expected)
        p = 0
        for row in range(n):
            for (name, ptype), s in zip(chans, sizes):
                dt = {0: "<u4", 1: "<f2", 2: "<f4"}[ptype]
                img[name][y - ymin + row] = np.frombuffer(data, dtype=dt, count=w, offset=p)
                p += w * s
    return np.stack([img["R"], img["G"], img["B"]], axis=-1)
