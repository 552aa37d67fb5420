#!/usr/bin/env bash
# Regenerates the measurements behind docs/accuracy.md: one `stagelight sweep` per knob on the
# example scenes. Tables (CSV/JSON) and plots (SVG) land in docs/accuracy/<name>/; the cached
# references stay there too (reference_*.exr, ignored by git). Takes several minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
bin=target/release/stagelight
out=docs/accuracy

sweep() {
    local name=$1; shift
    echo "== $name"
    "$bin" sweep "$@" --out "$out/$name" | tail -n 1
}

# Samples per pixel with the path tracer against a 256-spp path-traced reference.
sweep cornell_spp_path assets/scenes/cornell_box.ron --knob spp=1,2,4,8,16,32 --integrator path --reference-spp 256 --seeds 2
# The same knob with the direct-lighting integrator: it converges to a different (biased) image.
sweep cornell_spp_direct assets/scenes/cornell_box.ron --knob spp=1,4,16,64 --integrator direct --reference-spp 256
# Light samples per shading point (emitting ceiling quad), direct lighting, the scene's 16 spp.
sweep cornell_light_samples assets/scenes/cornell_box.ron --knob light_samples=1,4,16,64 --integrator direct --reference-spp 256
# BVH build quality: same image, different time.
sweep cornell_bvh assets/scenes/cornell_box.ron --knob bvh_quality=fast,medium,high --integrator direct --reference-spp 256
# Bake samples of the AO bake (1024², 146k triangles at the asset's 65k).
sweep bake_ao_samples assets/scenes/bake_ao.ron --knob bake_samples=4,16,64 --reference-spp 256
# Adaptive contrast against uniform spp on the depth-of-field scene, direct lighting, against a
# 512-spp direct-lighting reference (the knob trades noise, not the integrator's bias).
mkdir -p "$out/dof_spp"
ref="$out/dof_spp/reference_direct_512.exr"
[ -f "$ref" ] || "$bin" render assets/scenes/depth_of_field.ron --spp 512 -o "$ref"
sweep dof_adaptive_contrast assets/scenes/depth_of_field.ron --knob adaptive_contrast=0.2,0.1,0.05,0.02 --integrator direct --reference "$ref"
sweep dof_spp assets/scenes/depth_of_field.ron --knob spp=4,8,16,32 --integrator direct --reference "$ref"
