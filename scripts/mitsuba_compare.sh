#!/usr/bin/env bash
# Cornell box: stagelight's path tracer against Mitsuba 3 (docs/accuracy.md, "Against Mitsuba 3").
#   1. converged images: stagelight --integrator path at 1024 spp (two seeds), Mitsuba at 8192 spp;
#   2. relMSE between them next to the noise floor (stagelight seed 1 vs seed 2);
#   3. time to relMSE 1e-2: both renderers swept over spp in the same window.
# Needs PyPI (pip install mitsuba numpy) and, for llvm_ad_rgb, a libLLVM ≥ 16 (Debian: libllvm19;
# LLVM 14/15 fail with "Cannot select fminimum"). Falls back to scalar_rgb without it.
set -euo pipefail
cd "$(dirname "$0")/.."
# `mitsuba_compare.sh caustics`: the glass-ball caustics table instead (issue 16).
if [ "${1:-}" = caustics ]; then exec scripts/mitsuba_caustics.sh; fi
out=${OUT:-target/mitsuba}
mkdir -p "$out"
python3 -c "import mitsuba, numpy" 2>/dev/null || pip install --quiet mitsuba numpy
variant=scalar_rgb
for lib in /usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 /usr/lib/x86_64-linux-gnu/libLLVM-19.so; do
    if [ -e "$lib" ]; then export DRJIT_LIBLLVM_PATH=$lib; variant=llvm_ad_rgb; break; fi
done
cargo build --release --quiet
bin=target/release/stagelight
scene=assets/scenes/cornell_box.ron

python3 scripts/mitsuba_cornell.py "$out/mitsuba_8192.exr" --spp 8192 --variant "$variant"
for seed in 1 2; do
    "$bin" render "$scene" --integrator path --spp 1024 --seed "$seed" -o "$out/stagelight_1024_s$seed.exr"
done
echo "== stagelight 1024 spp vs Mitsuba 8192 spp"
python3 scripts/compare_exr.py "$out/stagelight_1024_s1.exr" "$out/mitsuba_8192.exr"
python3 scripts/compare_exr.py "$out/stagelight_1024_s2.exr" "$out/mitsuba_8192.exr"
echo "== noise floor: stagelight seed 1 vs seed 2 (= 2 × its variance)"
python3 scripts/compare_exr.py "$out/stagelight_1024_s1.exr" "$out/stagelight_1024_s2.exr"
echo "== time to relMSE 1e-2 (same reference, same window)"
"$bin" sweep "$scene" --knob spp=4,8,16,32 --integrator path --reference "$out/mitsuba_8192.exr" --out "$out/sweep"
python3 scripts/mitsuba_cornell.py "$out/unused.exr" --variant "$variant" --sweep 4,8,16,32 --seed 5 \
    --reference "$out/mitsuba_8192.exr"
