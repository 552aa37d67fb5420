#!/usr/bin/env python3
"""Compares RGB EXR images: relMSE (mean of (x−r)²/(r²+0.01), stagelight's sweep metric), MSE,
and per-channel means. Usage: compare_exr.py TEST.exr REFERENCE.exr [--png-diff OUT.png]"""
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")


def load(path):
    bmp = mi.Bitmap(path)
    arr = np.array(bmp, dtype=np.float64)
    return arr[:, :, :3]


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
