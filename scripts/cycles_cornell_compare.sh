#!/usr/bin/env bash
# Cornell box: stagelight's path tracer against Blender Cycles (docs/accuracy.md, "Against
# Blender Cycles"). `scripts/cycles_cornell.py` builds the same scene in Cycles from the RON.
#   1. converged images: stagelight at REF_SPP (two seeds), Cycles at REF_SPP, 2 threads; the
#      relMSE between them next to the noise floor (stagelight seed against seed);
#   2. time and error: SWEEP samples per pixel on 1 thread, ROUNDS alternated rounds, each
#      renderer against its own converged image — stagelight's `build_accel` + `shade`
#      seconds from `--stats-json`, Cycles' `bpy.ops.render.render` call (sync, BVH, samples).
# Needs Python 3.11 with `bpy==5.0.1` and numpy (installed from PyPI when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-target/cycles_cornell}
ref_spp=${REF_SPP:-2048}
sweep=${SWEEP:-4 16 64}
rounds=${ROUNDS:-2}
mkdir -p "$out"
python3 -c "import bpy, numpy" 2>/dev/null || pip install --quiet bpy==5.0.1 numpy
cargo build --release --quiet
bin=target/release/stagelight
scene=assets/scenes/cornell_box.ron

# ours SPP SEED THREADS NAME: renders $out/NAME.exr, prints build_accel + shade seconds.
ours() {
    "$bin" render "$scene" --integrator path --spp "$1" --seed "$2" --threads "$3" \
        -o "$out/$4.exr" --stats-json "$out/$4.json" >/dev/null 2>&1
    python3 -c "import json,sys; s={x['stage']: x['seconds'] for x in json.load(open(sys.argv[1]))['stages']}; print('%.3f' % (s['build_accel'] + s['shade']))" "$out/$4.json"
}
# cycles SPP SEED THREADS NAME: renders $out/NAME.exr, prints the render call's seconds.
cycles() {
    python3 scripts/cycles_cornell.py "$out/$4.exr" --spp "$1" --seed "$2" --threads "$3" 2>/dev/null |
        sed -n "s/^cycles_render_seconds \([0-9.]*\).*/\1/p"
}
err() { python3 scripts/compare_exr.py "$1" "$2" | cut -d' ' -f1-2; }

echo "== converged: $ref_spp spp, 2 threads"
ours "$ref_spp" 1 2 ref_s1 >/dev/null
ours "$ref_spp" 2 2 ref_s2 >/dev/null
cycles "$ref_spp" 1 2 ref_c >/dev/null
echo "stagelight vs Cycles:        $(python3 scripts/compare_exr.py "$out/ref_s1.exr" "$out/ref_c.exr")"
echo "stagelight seed 1 vs seed 2: $(python3 scripts/compare_exr.py "$out/ref_s1.exr" "$out/ref_s2.exr")"

echo "== time (s) and error against each one's own converged image, 1 thread"
for round in $(seq "$rounds"); do
    for n in $sweep; do
        s=$(ours "$n" $((10 + round)) 1 "s$n")
        c=$(cycles "$n" $((10 + round)) 1 "c$n")
        echo "round $round, $n spp: stagelight $s s $(err "$out/s$n.exr" "$out/ref_s2.exr") | Cycles $c s $(err "$out/c$n.exr" "$out/ref_c.exr")"
    done
done
