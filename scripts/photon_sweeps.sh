#!/usr/bin/env bash
# Regenerates the photon-knob sweeps of docs/accuracy.md ("Photon knobs"): `stagelight sweep`
# of `photons`, `gather_radius`, `gather_count`, `passes` and `filter` on the glass ball
# (scripts/glass_ball.ron), the error fitted on the caustic's floor pixels (`--crop
# 73,50,92,62`) against Mitsuba 3's light tracer there and its path tracer elsewhere
# (`mitsuba_glass_ball.py reference`; the references come from scripts/mitsuba_caustics.sh).
# Tables and per-knob plots land in docs/accuracy/glass_ball_<knob>/, the combined plot in
# docs/accuracy/glass_ball_knobs.svg (scripts/plot_sweeps.py). BIN=path/to/stagelight skips
# the release build; SEEDS (default 2) seeds per value.
set -euo pipefail
cd "$(dirname "$0")/.."
refs=${REFS:-target/mitsuba_caustics}
seeds=${SEEDS:-2}
if [ -z "${BIN:-}" ]; then
    cargo build --release --quiet
    BIN=target/release/stagelight
fi
[ -e "$refs/ref_path.exr" ] && [ -e "$refs/ref_ptracer.exr" ] || {
    echo "no references in $refs: run scripts/mitsuba_caustics.sh first" >&2
    exit 1
}
ref="$refs/ref_sweep.exr"
python3 scripts/mitsuba_glass_ball.py reference "$ref" "$refs/ref_path.exr" "$refs/ref_ptracer.exr"
scene=scripts/glass_ball.ron
# Progressive passes start from the map's radius: the automatic one (2 % of the scene's
# diagonal) is wider than this caustic, so that sweep starts from 0.02.
progressive="$refs/glass_ball_radius_0.02.ron"
sed 's/caustics: (photons: 100000, gather: 50)/caustics: (photons: 100000, gather: 50, radius: 0.02)/' \
    "$scene" > "$progressive"
grep -q 'radius: 0.02' "$progressive"
out=docs/accuracy
echo "load: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
sweep() { # NAME SCENE KNOB
    echo "== $1"
    "$BIN" sweep "$2" --knob "$3" --crop 73,50,92,62 --reference "$ref" --seeds "$seeds" \
        --out "$out/glass_ball_$1" 2>/dev/null | tail -n 1
}
sweep photons "$scene" photons=12500,25000,50000,100000,200000,400000
sweep gather_radius "$scene" gather_radius=0,0.01,0.02,0.04,0.08
sweep gather_count "$scene" gather_count=10,25,50,100,200
sweep passes "$progressive" passes=1,2,4,8
sweep filter "$scene" filter=box,cone,cone:2,gauss
# What the photon knobs compete with at the shipped 4 samples per pixel: camera samples.
sweep spp "$scene" spp=2,4,8,16,32
sixteen="$refs/glass_ball_16spp.ron"
sed 's/samples: 4,/samples: 16,/' "$scene" > "$sixteen"
grep -q 'samples: 16,' "$sixteen"
sweep photons_16spp "$sixteen" photons=12500,50000,200000
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 scripts/plot_sweeps.py "$out/glass_ball_knobs.svg" \
    "$out"/glass_ball_{photons,gather_radius,gather_count,passes,filter,spp,photons_16spp}/sweep.json
