#!/usr/bin/env bash
# AO bake: stagelight against Blender Cycles (docs/baking.md, "Against Blender Cycles").
# Both bake each texel at its centre (stagelight's `texel_samples: 1`; Cycles bakes the centre),
# without padding or seam stitching, so the two estimate the same values.
#   1. the mesh: `assets/scenes/bake_ao.ron`'s displaced rock (65,024 triangles), written once
#      by a per-vertex bake as PLY and turned into an OBJ (positions, UVs, normals) that both
#      bake: `rock.obj` (smooth normals) and `rock_flat.obj` (no normals: flat shading);
#   2. time: ROUNDS alternated bakes of RES² texels at SPP rays per texel on 1 thread —
#      stagelight's `build_accel` + `bake_lightmaps` seconds from `--stats-json`, Cycles'
#      `bpy.ops.object.bake(type="AO")` call (scene sync, its Embree BVH, the texels);
#   3. error: on REF_RES² texels, each baker at 16 … 256 rays per texel against its own
#      converged bake (REF_SPP rays, 2 threads) and the two converged bakes against each other,
#      on the flat mesh (both define AO the same way there; see the doc for smooth normals).
# Needs Python 3.11 with `bpy==5.0.1` and numpy (installed from PyPI when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-target/cycles_ao}
rounds=${ROUNDS:-3}
res=${RES:-1024}
spp=${SPP:-64}
ref_res=${REF_RES:-256}
ref_spp=${REF_SPP:-4096}
sweep=${SWEEP:-16 64 256}
mkdir -p "$out"
python3 -c "import bpy, numpy" 2>/dev/null || pip install --quiet bpy==5.0.1 numpy
cargo build --release --quiet
bin=$PWD/target/release/stagelight
here=$PWD/scripts

# 1. One mesh for both bakers.
sed -e 's/resolution: (1024, 1024),//' \
    -e 's/outputs: \[(kind: AmbientOcclusion(samples: 64))\]/outputs: [(kind: AmbientOcclusion(samples: 1), target: Vertices)]/' \
    assets/scenes/bake_ao.ron > "$out/mesh.ron"
"$bin" bake "$out/mesh.ron" -o "$out/mesh" 2>/dev/null
python3 "$here/ao_compare.py" obj "$out/mesh/rock_1_ao.ply" "$out/rock.obj"
grep -v '^vn' "$out/rock.obj" | sed -E 's#([0-9]+)/([0-9]+)/[0-9]+#\1/\2#g' > "$out/rock_flat.obj"

# A texture bake of MESH at RES² with SPP rays per texel and SEED, as a scene file.
scene() {
    cat <<RON
Scene(
    options: (seed: $4),
    cameras: [(name: "cam", fov_y: 35.0, resolution: (64, 64),
               placement: LookAt(eye: (0, -4.5, 2), target: (0, 0, 0), up: (0, 0, 1)))],
    materials: [(name: "stone", shader: Lambert(albedo: (0.6, 0.58, 0.55)))],
    objects: [(name: "rock", mesh: Obj(file: "$1"), material: "stone")],
    instances: [(name: "rock_1", of: "rock", bake: (
        resolution: ($2, $2), uvs: Mesh, texel_samples: 1, padding: 0, mask: true, stitch_seams: false,
        outputs: [(kind: AmbientOcclusion(samples: $3))],
    ))],
    groups: [(name: "world", members: ["rock_1"])],
    render: (root: "world", camera: "cam"),
)
RON
}
stage_seconds() {
    python3 -c "import json,sys; s={x['stage']: x['seconds'] for x in json.load(open(sys.argv[1]))['stages']}; print('%.3f' % (s['build_accel'] + s['bake_lightmaps']))" "$1"
}
# ours MESH RES SPP SEED THREADS DIR: bakes, prints the two stages' seconds.
ours() {
    scene "$1" "$2" "$3" "$4" > "$out/bake.ron"
    mkdir -p "$6"
    "$bin" bake "$out/bake.ron" -o "$6" --threads "$5" --stats-json "$6/stats.json" >"$6/log" 2>&1 ||
        { cat "$6/log" >&2; exit 1; }
    stage_seconds "$6/stats.json"
}
# cycles MESH RES SPP SEED THREADS OUT.npy: bakes, prints the bake call's seconds.
cycles() {
    python3 "$here/cycles_ao_bake.py" "$out/$1" "$6" --res "$2" --samples "$3" --seed "$4" \
        --threads "$5" 2>/dev/null | sed -n "s/^cycles_bake_seconds \([0-9.]*\).*/\1/p"
}

echo "== time: ${res}² texels, $spp rays per texel, 1 thread (seconds; rounds alternated)"
for round in $(seq "$rounds"); do
    s=$(ours rock.obj "$res" "$spp" 1 1 "$out/time_s")
    c=$(cycles rock.obj "$res" "$spp" 1 1 "$out/time_c.npy")
    python3 -c "import sys; s,c=map(float,sys.argv[1:]); print('round %s: stagelight %.3f  Cycles %.3f  ratio %.2fx' % ('$round', s, c, c/s))" "$s" "$c"
done
echo "== agreement at ${res}², $spp rays (smooth normals): stagelight vs Cycles"
python3 "$here/ao_compare.py" error "$out/time_s/rock_1_ao.exr" "$out/time_c.npy"

echo "== converged: ${ref_res}², $ref_spp rays per texel, flat mesh, 2 threads"
ours rock_flat.obj "$ref_res" "$ref_spp" 101 2 "$out/ref_s1" >/dev/null
ours rock_flat.obj "$ref_res" "$ref_spp" 102 2 "$out/ref_s2" >/dev/null
cycles rock_flat.obj "$ref_res" "$ref_spp" 101 2 "$out/ref_c.npy" >/dev/null
echo -n "stagelight vs Cycles:            "
python3 "$here/ao_compare.py" error "$out/ref_s1/rock_1_ao.exr" "$out/ref_c.npy"
echo -n "stagelight seed 101 vs seed 102: "
python3 "$here/ao_compare.py" error "$out/ref_s1/rock_1_ao.exr" "$out/ref_s2/rock_1_ao.exr"

echo "== error against time: ${ref_res}², flat mesh, 1 thread, each against its own converged bake"
for n in $sweep; do
    s=$(ours rock_flat.obj "$ref_res" "$n" 7 1 "$out/sweep_s$n")
    c=$(cycles rock_flat.obj "$ref_res" "$n" 7 1 "$out/sweep_c$n.npy")
    echo "$n rays: stagelight $s s  $(python3 "$here/ao_compare.py" error "$out/sweep_s$n/rock_1_ao.exr" "$out/ref_s2/rock_1_ao.exr")"
    echo "$n rays: Cycles     $c s  $(python3 "$here/ao_compare.py" error "$out/sweep_c$n.npy" "$out/ref_c.npy")"
done
