#!/usr/bin/env python3
"""Compares RGB EXR images: relMSE (mean of (x−r)²/(r²+0.01), stagelight's sweep metric), MSE,
and per-channel means. Usage: compare_exr.py TEST.exr REFERENCE.exr
Scan-line EXRs (stagelight's, Blender's) are read by `exr_f32.py`; others need Mitsuba."""
import os
import struct
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import exr_f32  # noqa: E402


def load(path):
    try:
        return exr_f32.load_rgb(path)
    except (KeyError, ValueError, struct.error):
        import mitsuba as mi

        mi.set_variant("scalar_rgb")
        return np.array(mi.Bitmap(path), dtype=np.float64)[:, :, :3]


def main():
    a, r = load(sys.argv[1]), load(sys.argv[2])
    if a.shape != r.shape:
        sys.exit("shape mismatch %s vs %s" % (a.shape, r.shape))
    d = a - r
    rel = np.mean(d * d / (r * r + 1e-2))
    print("relMSE %.4e  MSE %.4e  mean test %s  mean ref %s  ratio %s" % (
        rel, np.mean(d * d), a.mean(axis=(0, 1)).round(5), r.mean(axis=(0, 1)).round(5),
        (a.mean(axis=(0, 1)) / r.mean(axis=(0, 1))).round(4)))


if __name__ == "__main__":
    main()
