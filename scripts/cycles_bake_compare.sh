#!/usr/bin/env bash
# Bakes: stagelight against Blender Cycles (docs/baking.md, "Against Blender Cycles").
#   1. the mesh: `assets/scenes/bake_ao.ron`'s displaced rock (65,024 triangles), written once
#      by a per-vertex bake as PLY and turned into an OBJ (positions, UVs, normals) that both
#      bake: `rock.obj` (smooth normals) and `rock_flat.obj` (no normals: flat shading);
#   2. ambient occlusion, then 3. a lightmap (the scene's sun, irradiance, with and without
#      two bounces of indirect light; Cycles' diffuse bake without its colour pass, E/π):
#      - time: ROUNDS alternated bakes of RES² texels at SPP rays (gather paths) per texel on
#        1 thread — stagelight's `build_accel` + `bake_lightmaps` seconds from `--stats-json`,
#        the wall time of Cycles' `bpy.ops.object.bake` call (scene sync, its Embree BVH, the
#        texels);
#      - agreement: on REF_RES² texels, the converged bakes (REF_SPP, 2 threads) against each
#        other and two stagelight seeds against each other (the noise floor); the direct
#        lightmap (no noise in either) texel by texel;
#      - error against time: each baker at SWEEP rays per texel against its own converged
#        bake, 1 thread, on the flat mesh (there both define the values the same way; the doc
#        says where smooth normals differ).
# stagelight bakes each texel at its centre (`texel_samples: 1`), as Cycles' one-sample bake
# does from 256² on; neither pads nor stitches seams. PARTS="ao lightmap" picks the sections.
# Needs Python 3.11 with `bpy==5.0.1` and numpy (installed from PyPI when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-target/cycles_bake}
rounds=${ROUNDS:-3}
res=${RES:-1024}
spp=${SPP:-64}
ref_res=${REF_RES:-256}
ref_spp=${REF_SPP:-4096}
sweep=${SWEEP:-16 64 256}
parts=${PARTS:-ao lightmap}
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
python3 "$here/bake_compare.py" obj "$out/mesh/rock_1_ao.ply" "$out/rock.obj"
grep -v '^vn' "$out/rock.obj" | sed -E 's#([0-9]+)/([0-9]+)/[0-9]+#\1/\2#g' > "$out/rock_flat.obj"

# The bake output of KIND with N rays per texel: `ao`, `lightmap` (direct) or `indirect`.
output() {
    case $1 in
    ao) echo "AmbientOcclusion(samples: $2)" ;;
    lightmap) echo "Lightmap(indirect: false, samples: 1, store: Irradiance)" ;;
    indirect) echo "Lightmap(indirect: true, samples: $2, max_depth: 2, store: Irradiance)" ;;
    esac
}
# A texture bake of MESH at RES² of KIND with N rays per texel and SEED, as a scene file.
scene() {
    cat <<RON
Scene(
    options: (seed: $5),
    cameras: [(name: "cam", fov_y: 35.0, resolution: (64, 64),
               placement: LookAt(eye: (0, -4.5, 2), target: (0, 0, 0), up: (0, 0, 1)))],
    lights: [(name: "sun", kind: Directional(direction: (0.4, 0.6, -1)), intensity: 2.5)],
    materials: [(name: "stone", shader: Lambert(albedo: (0.6, 0.58, 0.55)))],
    objects: [(name: "rock", mesh: Obj(file: "$1"), material: "stone")],
    instances: [(name: "rock_1", of: "rock", bake: (
        resolution: ($2, $2), uvs: Mesh, texel_samples: 1, padding: 0, mask: true, stitch_seams: false,
        outputs: [(kind: $(output "$3" "$4"))],
    ))],
    groups: [(name: "world", members: ["rock_1"])],
    render: (root: "world", camera: "cam"),
)
RON
}
# ours KIND MESH RES N SEED THREADS DIR: bakes, prints the two stages' seconds.
ours() {
    mkdir -p "$7"
    scene "$2" "$3" "$1" "$4" "$5" > "$out/bake.ron"
    "$bin" bake "$out/bake.ron" -o "$7" --threads "$6" --stats-json "$7/stats.json" >"$7/log" 2>&1 ||
        { cat "$7/log" >&2; exit 1; }
    python3 -c "import json,sys; s={x['stage']: x['seconds'] for x in json.load(open(sys.argv[1]))['stages']}; print('%.3f' % (s['build_accel'] + s['bake_lightmaps']))" "$7/stats.json"
}
# cycles KIND MESH RES N SEED THREADS OUT.npy: bakes, prints the bake call's seconds.
cycles() {
    local kind=(--kind ao)
    case $1 in
    lightmap) kind=(--kind lightmap) ;;
    indirect) kind=(--kind lightmap --indirect --bounces 2) ;;
    esac
    python3 "$here/cycles_bake.py" "$out/$2" "$7" "${kind[@]}" --res "$3" --samples "$4" \
        --seed "$5" --threads "$6" 2>/dev/null | sed -n "s/^cycles_bake_seconds \([0-9.]*\).*/\1/p"
}
file() { case $1 in ao) echo rock_1_ao.exr ;; *) echo rock_1_lightmap.exr ;; esac; }
compare() { python3 "$here/bake_compare.py" error "$1" "$2"; }

# time KIND: ROUNDS alternated bakes at RES², SPP, 1 thread, smooth normals.
time_rounds() {
    echo "== $1: time, ${res}² texels, $spp rays per texel, 1 thread (seconds; rounds alternated)"
    for round in $(seq "$rounds"); do
        s=$(ours "$1" rock.obj "$res" "$spp" 1 1 "$out/$1_time_s")
        c=$(cycles "$1" rock.obj "$res" "$spp" 1 1 "$out/$1_time_c.npy")
        python3 -c "import sys; s,c=map(float,sys.argv[2:]); print('round %s: stagelight %.3f  Cycles %.3f  ratio %.2fx' % (sys.argv[1], s, c, c/s))" "$round" "$s" "$c"
    done
    echo "agreement at ${res}², $spp rays, smooth normals: $(compare "$out/$1_time_s/$(file "$1")" "$out/$1_time_c.npy")"
}
# converged KIND: both at REF_SPP, two stagelight seeds, flat normals.
converged() {
    echo "== $1: converged, ${ref_res}², $ref_spp rays per texel, flat mesh, 2 threads"
    ours "$1" rock_flat.obj "$ref_res" "$ref_spp" 101 2 "$out/$1_ref_s1" >/dev/null
    ours "$1" rock_flat.obj "$ref_res" "$ref_spp" 102 2 "$out/$1_ref_s2" >/dev/null
    cycles "$1" rock_flat.obj "$ref_res" "$ref_spp" 101 2 "$out/$1_ref_c.npy" >/dev/null
    echo "stagelight vs Cycles:            $(compare "$out/$1_ref_s1/$(file "$1")" "$out/$1_ref_c.npy")"
    echo "stagelight seed 101 vs seed 102: $(compare "$out/$1_ref_s1/$(file "$1")" "$out/$1_ref_s2/$(file "$1")")"
}
# sweep KIND: error against time, flat normals, 1 thread.
sweep() {
    echo "== $1: error against time, ${ref_res}², flat mesh, 1 thread, each against its own converged bake"
    for n in $sweep; do
        s=$(ours "$1" rock_flat.obj "$ref_res" "$n" 7 1 "$out/$1_sweep_s$n")
        c=$(cycles "$1" rock_flat.obj "$ref_res" "$n" 7 1 "$out/$1_sweep_c$n.npy")
        echo "$n rays: stagelight $s s  $(compare "$out/$1_sweep_s$n/$(file "$1")" "$out/$1_ref_s2/$(file "$1")")"
        echo "$n rays: Cycles     $c s  $(compare "$out/$1_sweep_c$n.npy" "$out/$1_ref_c.npy")"
    done
}

for part in $parts; do
    case $part in
    ao)
        time_rounds ao
        converged ao
        sweep ao
        ;;
    lightmap)
        echo "== direct lightmap (one shadow ray per texel, no noise in either), ${ref_res}²"
        for mesh in rock_flat.obj rock.obj; do
            ours lightmap "$mesh" "$ref_res" 1 1 1 "$out/direct_s_$mesh" >/dev/null
            cycles lightmap "$mesh" "$ref_res" 1 1 1 "$out/direct_c_$mesh.npy" >/dev/null
            echo "$mesh: $(compare "$out/direct_s_$mesh/rock_1_lightmap.exr" "$out/direct_c_$mesh.npy")"
        done
        time_rounds indirect
        converged indirect
        sweep indirect
        ;;
    esac
done
