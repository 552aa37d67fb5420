#!/usr/bin/env python3
"""Issue 17's per-ray ledger in one window: Embree 3 (its default mode and its robust mode)
against stagelight's `bvh` bench, in alternated rounds, on the anchor's mesh and ray files.

Embree's default single-ray kernel (`BVH8Triangle4Intersector1Moeller`) is not watertight: on
the anchor's incoherent rays it misses one ray that starts inside the closed mesh and crosses it
next to a shared edge. `RTC_SCENE_FLAG_ROBUST` ("avoids optimizations that reduce arithmetic
accuracy") switches it to `BVH8Triangle4vIntersector1Pluecker` with a conservative node test,
which finds that hit as stagelight's watertight test does: the like-for-like peer. The
anchor's `embree_bench.c` is compiled twice into BUILD_DIR, once as it is and once with the
robust flag set after `rtcNewScene` (the anchor is not changed).

Per round: Embree default, Embree robust, then each stagelight bench binary
(`--bench summary`, 1 thread, `Medium`, single-ray API); each prints the best of REPS.
Printed: every round's Mrays per CPU-second, then per stagelight binary and query the ratio
to each Embree mode of each round (against the Embree runs of the same round) as a range and
its median. Several binaries (a before and an after) are compared in the same window.

`REPS=1` measures the first build of each process, the one build a render does (best-of-three
builds reuse memory the first one faulted in).

usage: scripts/embree_compare.py [ROUNDS]   (default 3)
  env: DATA_DIR (default ${TMPDIR:-/tmp}/bvh_anchor_data; generated when missing),
       BUILD_DIR (default ${TMPDIR:-/tmp}/embree_compare_build), REPS (default 3),
       BENCH (built `bvh` bench binaries, space-separated; default: this checkout's, built
       with `cargo bench --no-run`)
"""

import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ANCHOR = os.path.join(ROOT, "..", "shared", "anchors", "embree")
TMP = os.environ.get("TMPDIR", "/tmp")
DATA = os.environ.get("DATA_DIR", os.path.join(TMP, "bvh_anchor_data"))
BUILD = os.environ.get("BUILD_DIR", os.path.join(TMP, "embree_compare_build"))
REPS = os.environ.get("REPS", "3")
QUERIES = ("coherent", "incoherent", "occluded")
NEW_SCENE = "RTCScene scene = rtcNewScene(dev);"


def fail(msg):
    sys.exit(f"error: {msg}")


def run(cmd, env=None):
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        fail(f"{' '.join(cmd)} failed:\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    return p.stdout + p.stderr


def build_embree():
    """The anchor's benchmark as it is (`default`) and with the robust scene flag (`robust`)."""
    if not os.path.exists("/usr/include/embree3/rtcore.h"):
        fail("missing Embree 3 headers: apt-get install libembree-dev gcc")
    with open(os.path.join(ANCHOR, "embree_bench.c")) as f:
        source = f.read()
    if source.count(NEW_SCENE) != 1:
        fail(f"the anchor's embree_bench.c no longer has one '{NEW_SCENE}' line to patch")
    os.makedirs(BUILD, exist_ok=True)
    bins = {}
    for mode, text in (
        ("default", source),
        ("robust", source.replace(
            NEW_SCENE, NEW_SCENE + "\n  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);")),
    ):
        src = os.path.join(BUILD, f"embree_bench_{mode}.c")
        with open(src, "w") as f:
            f.write(text)
        exe = os.path.join(BUILD, f"embree_bench_{mode}")
        run(["gcc", "-O2", "-Wall", "-fopenmp", "-o", exe, src, "-lembree3", "-lm"])
        bins[mode] = exe
    return bins


def build_benches():
    if os.environ.get("BENCH"):
        benches = os.environ["BENCH"].split()
        for b in benches:
            if not os.access(b, os.X_OK):
                fail(f"BENCH: '{b}' is not an executable bench binary")
        return benches
    out = run(["cargo", "bench", "--bench", "bvh", "--no-run", "--manifest-path",
               os.path.join(ROOT, "Cargo.toml")])
    m = re.search(r"Executable benches/bvh\.rs \(([^)]+)\)", out)
    if not m:
        fail("cargo did not name the bvh bench executable")
    path = m.group(1)
    return [path if os.path.isabs(path) else os.path.join(ROOT, path)]


def embree_round(exe):
    out = run([exe, DATA, "1", "medium", "", REPS])
    r = {"build": float(re.search(r"([\d.]+) ms process cpu", out).group(1))}
    for q, pat in zip(QUERIES, ("coherent  closest", "incoherent closest", "incoherent occluded")):
        m = re.search(re.escape(pat) + r".*?\|\s+([\d.]+) Mrays/cpu-s \| hits=(\d+)", out)
        if not m:
            fail(f"no '{pat}' line in Embree's output:\n{out}")
        r[q] = float(m.group(1))
        r[q + "_hits"] = int(m.group(2))
    return r


def ours_round(bench):
    env = dict(os.environ, STAGELIGHT_BENCH_DATA=DATA, STAGELIGHT_BENCH_QUALITIES="medium",
               STAGELIGHT_BENCH_THREADS="1", STAGELIGHT_BENCH_API="single",
               STAGELIGHT_BENCH_REPS=REPS)
    out = run([bench, "--bench", "summary"], env=env)
    r = {"build": float(re.search(r"threads=1: \d+ ms wall, (\d+) ms cpu", out).group(1))}
    for q in QUERIES:
        m = re.search(r"medium " + q + r"\s+threads=1:.*?([\d.]+) Mrays/cpu-s, hits (\d+)", out)
        if not m:
            fail(f"no '{q}' line in the bench's output:\n{out}")
        r[q] = float(m.group(1))
        r[q + "_hits"] = int(m.group(2))
    return r


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    if rounds < 1:
        fail("ROUNDS must be at least 1")
    if not os.path.exists(os.path.join(DATA, "rays_incoherent.bin")):
        run(["python3", os.path.join(ANCHOR, "gen_scene.py"), DATA])
    embree = build_embree()
    benches = build_benches()
    ours = [f"stagelight{i + 1}" if len(benches) > 1 else "stagelight"
            for i in range(len(benches))]
    rows = []
    for i in range(rounds):
        row = {mode: embree_round(exe) for mode, exe in embree.items()}
        for name, bench in zip(ours, benches):
            row[name] = ours_round(bench)
        rows.append(row)
        print(f"round {i + 1}: " + "; ".join(
            f"{who} build {r['build']:.0f} ms, "
            + " / ".join(f"{r[q]:.2f}" for q in QUERIES)
            for who, r in row.items()), flush=True)
    if len(benches) > 1:
        print()
        for name, bench in zip(ours, benches):
            print(f"{name}: {bench}")
    print("\nMrays per CPU-second (coherent / incoherent / occlusion), 1 thread, Medium;"
          " hits of the last round:")
    for who in ["default", "robust"] + ours:
        r = rows[-1][who]
        print(f"  {who:11} hits " + " / ".join(str(r[q + '_hits']) for q in QUERIES))
    print("\nstagelight / Embree per round (range, median); build: stagelight's CPU time"
          " / Embree's:")
    for name in ours:
        for mode in ("default", "robust"):
            for q in QUERIES + ("build",):
                ratios = [row[name][q] / row[mode][q] for row in rows]
                print(f"  {name:11} / {mode:8} {q:10} {min(ratios):.2f}–{max(ratios):.2f}×"
                      f" (median {statistics.median(ratios):.2f}×)")


if __name__ == "__main__":
    main()
