#!/usr/bin/env python3
"""Statistics for scripts/path_stats_ab.sh: DIR NAME REF_SPP SEEDS. relMSE (mean of
(x−r)²/(r²+0.01), the sweep metric) of every base and new render against the reference, and
per channel Z = mean(new − base) / (std(base − ref) / √pixels) over all seeds. Exit 1 when a
|Z| ≥ 3 or the mean relMSE of new exceeds base's by more than 5 %."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from exr_f32 import load_rgb  # noqa: E402


def rel_mse(x, r):
    return float(np.mean((x - r) ** 2 / (r * r + 1e-2)))


def main():
    d, name, ref_spp, seeds = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    ref = load_rgb(os.path.join(d, "%s_ref%s.exr" % (name, ref_spp)))
    base = [load_rgb(os.path.join(d, "%s_base_%d.exr" % (name, k))) for k in range(1, seeds + 1)]
    new = [load_rgb(os.path.join(d, "%s_new_%d.exr" % (name, k))) for k in range(1, seeds + 1)]
    rb = [rel_mse(b, ref) for b in base]
    rn = [rel_mse(n, ref) for n in new]
    diff = np.stack([n - b for n, b in zip(new, base)])
    noise = np.stack([b - ref for b in base])
    pixels = diff[..., 0].size
    sigma = noise.reshape(-1, 3).std(axis=0) / np.sqrt(pixels)
    z = diff.reshape(-1, 3).mean(axis=0) / sigma
    bitwise = sum(int(np.array_equal(n, b)) for n, b in zip(new, base))
    ok = np.all(np.abs(z) < 3) and np.mean(rn) <= 1.05 * np.mean(rb)
    print("%-14s relMSE base %s mean %.4e | new %s mean %.4e | ratio %.4f | Z(R,G,B) %s | "
          "max|new-base| %.2e | identical %d/%d  %s" % (
              name, " ".join("%.4e" % x for x in rb), np.mean(rb),
              " ".join("%.4e" % x for x in rn), np.mean(rn), np.mean(rn) / np.mean(rb),
              np.array2string(z, precision=2), np.abs(diff).max(), bitwise, seeds,
              "ok" if ok else "FAIL"))
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
