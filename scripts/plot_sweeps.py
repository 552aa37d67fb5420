#!/usr/bin/env python3
"""Draws several `stagelight sweep` results (their sweep.json) on one log–log plot: relMSE
against seconds, one line per knob, two panels — the fitted region (the crop when the sweep
had `--crop`) and the whole image. Plain SVG, no plotting library.

Usage: plot_sweeps.py OUT.svg SWEEP.json…
"""
import json
import math
import sys

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf"]
PANEL_W, PANEL_H, MARGIN_L, MARGIN_B, MARGIN_T = 430, 330, 64, 46, 34


def load(path):
    with open(path) as f:
        s = json.load(f)
    rows = s["rows"]
    fitted = [(r.get("crop_error") or r["error"])["rel_mse"] for r in rows]
    whole = [r["error"]["rel_mse"] for r in rows]
    return {
        "knob": s["knob"],
        "region": "crop %(x0)d,%(y0)d,%(x1)d,%(y1)d" % s["crop"] if s.get("crop") else "whole image",
        "labels": [r["value"] for r in rows],
        "seconds": [r["seconds"] for r in rows],
        "fitted": fitted,
        "whole": whole,
    }


def decades(lo, hi):
    return list(range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1))


def panel(sweeps, key, title, ox):
    xs = [x for s in sweeps for x in s["seconds"] if x > 0]
    ys = [y for s in sweeps for y in s[key] if y > 0]
    xd, yd = decades(min(xs), max(xs)), decades(min(ys), max(ys))
    if len(xd) < 2:
        xd.append(xd[-1] + 1)
    if len(yd) < 2:
        yd.append(yd[-1] + 1)
    x0, x1, y0, y1 = xd[0], xd[-1], yd[0], yd[-1]
    w, h = PANEL_W - MARGIN_L - 16, PANEL_H - MARGIN_B - MARGIN_T

    def px(x):
        return ox + MARGIN_L + (math.log10(x) - x0) / (x1 - x0) * w

    def py(y):
        return MARGIN_T + h - (math.log10(y) - y0) / (y1 - y0) * h

    out = ['<text x="%.1f" y="20" font-size="14" text-anchor="middle">%s</text>'
           % (ox + MARGIN_L + w / 2, title)]
    out.append('<rect x="%.1f" y="%d" width="%d" height="%d" fill="none" stroke="#444"/>'
               % (ox + MARGIN_L, MARGIN_T, w, h))
    for d in xd:
        x = ox + MARGIN_L + (d - x0) / (x1 - x0) * w
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' % (x, MARGIN_T, x, MARGIN_T + h))
        out.append('<text x="%.1f" y="%d" font-size="11" text-anchor="middle">1e%d</text>' % (x, MARGIN_T + h + 16, d))
    for d in yd:
        y = MARGIN_T + h - (d - y0) / (y1 - y0) * h
        out.append('<line x1="%.1f" y1="%.1f" x2="%.1f" y2="%.1f" stroke="#ddd"/>' % (ox + MARGIN_L, y, ox + MARGIN_L + w, y))
        out.append('<text x="%.1f" y="%.1f" font-size="11" text-anchor="end">1e%d</text>' % (ox + MARGIN_L - 6, y + 4, d))
    out.append('<text x="%.1f" y="%d" font-size="12" text-anchor="middle">seconds</text>'
               % (ox + MARGIN_L + w / 2, MARGIN_T + h + 36))
    out.append('<text x="%.1f" y="%.1f" font-size="12" text-anchor="middle" transform="rotate(-90 %.1f %.1f)">relMSE</text>'
               % (ox + 16, MARGIN_T + h / 2, ox + 16, MARGIN_T + h / 2))
    for i, s in enumerate(sweeps):
        c = COLOURS[i % len(COLOURS)]
        pts = [(px(x), py(y), lab) for x, y, lab in zip(s["seconds"], s[key], s["labels"]) if x > 0 and y > 0]
        out.append('<polyline fill="none" stroke="%s" stroke-width="1.5" points="%s"/>'
                   % (c, " ".join("%.1f,%.1f" % (x, y) for x, y, _ in pts)))
        for x, y, lab in pts:
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (x, y, c))
            out.append('<text x="%.1f" y="%.1f" font-size="9" fill="%s">%s</text>' % (x + 4, y - 4, c, lab))
        ly = MARGIN_T + 14 + 14 * i
        lx = ox + MARGIN_L + w - 110
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="%s" stroke-width="2"/>' % (lx, ly - 4, lx + 16, ly - 4, c))
        out.append('<text x="%.1f" y="%d" font-size="11">%s</text>' % (lx + 20, ly, s["knob"]))
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    sweeps = [load(p) for p in sys.argv[2:]]
    regions = sorted({s["region"] for s in sweeps})
    body = panel(sweeps, "fitted", "relMSE of the %s vs seconds" % " / ".join(regions), 0)
    body += panel(sweeps, "whole", "relMSE of the whole image vs seconds", PANEL_W)
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif">'
           % (2 * PANEL_W, PANEL_H), '<rect width="100%" height="100%" fill="white"/>'] + body + ["</svg>"]
    with open(sys.argv[1], "w") as f:
        f.write("\n".join(svg) + "\n")
    print("wrote %s (%d sweeps)" % (sys.argv[1], len(sweeps)))


if __name__ == "__main__":
    main()
