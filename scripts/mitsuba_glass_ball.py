#!/usr/bin/env python3
"""Renders scripts/glass_ball.ron (a glass ball on a floor under a small panel light) with
Mitsuba 3, and compares EXR images on the whole frame and on the caustic crop.

The scene is written out by hand here (keep it in step with glass_ball.ron): the floor and
wall are rectangles (one-sided diffuse, as stagelight's Lambert with `face: Front`), the ball
an analytic sphere (stagelight tessellates it finely, 96 × 48), the panel a one-sided
rectangle emitter of radiance 800 (stagelight's Rect `intensity`). Mitsuba's `max_depth`
counts path segments, stagelight's counts vertices: Mitsuba gets stagelight's 8 + 1. Box pixel
filter on both.

Usage:
  mitsuba_glass_ball.py render OUT.exr --integrator path|ptracer --spp N [--seed S]
  mitsuba_glass_ball.py compare TEST.exr WHOLE_REF.exr CROP_REF.exr
  mitsuba_glass_ball.py reference OUT.exr WHOLE_REF.exr CROP_REF.exr
(`render` prints the seconds the render took, the scene load and kernel compile excluded;
`compare` prints relMSE — mean of (x−r)²/(r²+0.01) — of the whole image against WHOLE_REF and
of the caustic crop against CROP_REF, the crop's pixels that see the ball left out: a light
tracer cannot render glass, so CROP_REF is black there; the error with them is printed too;
and of the whole image against the best reference: CROP_REF wherever the ball is not seen,
WHOLE_REF where it is (the path tracer misses the caustic on the floor).
`reference` writes the reference of `stagelight sweep --crop 73,50,92,62` (SWEEP_CROP, the
crop's floor pixels only): WHOLE_REF with that rectangle taken from CROP_REF.)
"""
import argparse
import sys
import time

# Caustic crop, pixels [x0, x1) × [y0, y1) of the 128 × 96 image (the bright spot right of
# the ball and its surroundings).
CROP = (71, 92, 50, 62)
# The same crop without the columns that see the ball (x0, y0, x1, y1 as `--crop` takes it).
SWEEP_CROP = (73, 50, 92, 62)


def scene_dict(mi, integrator, spp, seed):
    T = mi.ScalarTransform4f
    diffuse = lambda rgb: {"type": "diffuse", "reflectance": {"type": "rgb", "value": rgb}}
    return {
        "type": "scene",
        "integrator": {"type": integrator, "max_depth": 9},
        "sensor": {
            "type": "perspective",
            "fov_axis": "y",
            "fov": 40.0,
            "to_world": T().look_at(origin=[0, -3.5, 2.2], target=[0.2, 0, 0.3], up=[0, 0, 1]),
            "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
            "film": {"type": "hdrfilm", "width": 128, "height": 96, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
        },
        "floor": {"type": "rectangle", "to_world": T().scale([3, 3, 1]),
                  "bsdf": diffuse([0.7, 0.7, 0.7])},
        "wall": {"type": "rectangle",
                 "to_world": T().translate([0, 2, 1.5]).rotate([1, 0, 0], 90).scale([3, 1.5, 1]),
                 "bsdf": diffuse([0.7, 0.3, 0.2])},
        "ball": {"type": "sphere", "center": [0, 0, 0.5], "radius": 0.5,
                 "bsdf": {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0}},
        "panel": {"type": "rectangle",
                  "to_world": T().translate([-2.5, 0, 2.5]).rotate([1, 0, 0], 180).scale([0.1, 0.1, 1]),
                  "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [800, 800, 800]}}},
    }


def render(args):
    import mitsuba as mi
    mi.set_variant(args.variant)
    scene = mi.load_dict(scene_dict(mi, args.integrator, args.spp, args.seed))
    start = time.time()
    image = mi.render(scene, spp=args.spp, seed=args.seed)
    seconds = time.time() - start
    mi.Bitmap(image).write(args.out)
    print("%s %d spp: %.2f s" % (args.integrator, args.spp, seconds))


def load(mi, path):
    import numpy as np
    return np.array(mi.Bitmap(path), dtype=np.float64)[:, :, :3]


def rel_mse(a, r):
    import numpy as np
    d = a - r
    return float(np.mean(d * d / (r * r + 1e-2)))


def ball_pixels(mi):
    """Pixels any part of which sees the ball (Mitsuba's depth AOV of the ball alone, 64
    spp): a light tracer renders them black (it cannot see glass), so the crop's
    light-tracer reference is wrong there and they are left out of the crop error."""
    import numpy as np
    d = scene_dict(mi, "path", 64, 0)
    d = {k: v for k, v in d.items() if k in ("type", "sensor", "ball")}
    d["integrator"] = {"type": "aov", "aovs": "dd.y:depth"}
    depth = np.array(mi.render(mi.load_dict(d), spp=64))
    return depth[:, :, 0] > 0


def compare(args):
    import numpy as np
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    test, whole, crop_ref = load(mi, args.test), load(mi, args.whole), load(mi, args.crop)
    x0, x1, y0, y1 = CROP
    crop = lambda img: img[y0:y1, x0:x1]
    floor = ~crop(ball_pixels(mi))
    masked = lambda img: crop(img)[floor]
    ball = ball_pixels(mi)
    # The best reference of the whole image: the light tracer wherever it is valid (every
    # pixel that does not see the ball: it converges the caustic, which the path tracer
    # misses), the path tracer where the ball is seen.
    best = np.where(ball[:, :, None], whole, crop_ref)
    print("whole %.3e  crop %.3e  crop mean %.4f (ref %.4f)  [crop with the %d ball pixels: %.3e]"
          "  whole vs best ref %.3e" % (
              rel_mse(test, whole), rel_mse(masked(test), masked(crop_ref)), masked(test).mean(),
              masked(crop_ref).mean(), int((~floor).sum()), rel_mse(crop(test), crop(crop_ref)),
              rel_mse(test, best)))


def reference(args):
    import numpy as np
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    whole, crop_ref = load(mi, args.whole), load(mi, args.crop)
    x0, y0, x1, y1 = SWEEP_CROP
    out = whole.copy()
    out[y0:y1, x0:x1] = crop_ref[y0:y1, x0:x1]
    mi.Bitmap(out.astype(np.float32)).write(args.out)
    print("wrote %s (crop %d,%d,%d,%d from %s)" % (args.out, x0, y0, x1, y1, args.crop))


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("render")
    r.add_argument("out")
    r.add_argument("--integrator", default="path", choices=["path", "ptracer"])
    r.add_argument("--spp", type=int, default=64)
    r.add_argument("--seed", type=int, default=0)
    r.add_argument("--variant", default="scalar_rgb")
    c = sub.add_parser("compare")
    c.add_argument("test")
    c.add_argument("whole")
    c.add_argument("crop")
    f = sub.add_parser("reference")
    f.add_argument("out")
    f.add_argument("whole")
    f.add_argument("crop")
    args = ap.parse_args()
    return {"render": render, "compare": compare, "reference": reference}[args.cmd](args)


if __name__ == "__main__":
    sys.exit(main())
