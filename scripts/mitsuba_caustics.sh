#!/usr/bin/env bash
# Glass ball on a floor (scripts/glass_ball.ron): stagelight's photon maps and path tracer
# against Mitsuba 3's path tracer and light tracer (ptracer), issue 16's "Done when" table
# (docs/accuracy.md, "Caustics against Mitsuba 3").
#   1. references: Mitsuba path at REF_SPP (whole image), Mitsuba ptracer at REF_SPP (the
#      caustic crop: a light tracer converges a caustic on a diffuse floor fastest);
#   2. one run of each method (settings below, chosen for similar times), wall time and
#      relMSE of the whole image and of the caustic crop.
# Times: wall and CPU of each whole process (stagelight: load, tessellation, BVH, photons,
# shading; Mitsuba: import, scene load, render); the .log files hold Mitsuba's render-call time.
# Needs PyPI (pip install mitsuba numpy). BIN=path/to/stagelight skips the release build.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-target/mitsuba_caustics}
ref_spp=${REF_SPP:-2048}
mkdir -p "$out"
python3 -c "import mitsuba, numpy" 2>/dev/null || pip install --quiet mitsuba numpy
if [ -z "${BIN:-}" ]; then
    cargo build --release --quiet
    BIN=target/release/stagelight
fi
py=scripts/mitsuba_glass_ball.py
scene=scripts/glass_ball.ron
echo "load: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
[ -e "$out/ref_path.exr" ] || python3 $py render "$out/ref_path.exr" --integrator path --spp "$ref_spp" --seed 101
[ -e "$out/ref_ptracer.exr" ] || python3 $py render "$out/ref_ptracer.exr" --integrator ptracer --spp "$ref_spp" --seed 102
timed() { # NAME COMMAND…: runs the command, prints its wall and CPU (user+sys) seconds
    local name=$1; shift
    /usr/bin/time -f "$name: %e s wall, %U + %S s CPU" "$@" > "$out/$name.log" 2> "$out/$name.time"
    tail -1 "$out/$name.time"
}
timed stagelight_photons "$BIN" render "$scene" -o "$out/stagelight_photons.exr"
timed stagelight_path "$BIN" render "$scene" --integrator path --spp "${PATH_SPP:-32}" -o "$out/stagelight_path.exr"
timed mitsuba_path python3 $py render "$out/mitsuba_path.exr" --integrator path --spp "${MTS_PATH_SPP:-64}"
timed mitsuba_ptracer python3 $py render "$out/mitsuba_ptracer.exr" --integrator ptracer --spp "${MTS_PT_SPP:-64}"
for name in stagelight_photons stagelight_path mitsuba_path mitsuba_ptracer; do
    echo "$name: $(python3 $py compare "$out/$name.exr" "$out/ref_path.exr" "$out/ref_ptracer.exr")"
done
echo "noise floor (the two references): $(python3 $py compare "$out/ref_ptracer.exr" "$out/ref_path.exr" "$out/ref_path.exr")"
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
