#!/usr/bin/env bash
# Measures farm scaling on this machine and fits the model in docs/farm.md:
#   T(N) = load + overhead + render / N + merge_per_part · N
# where `load` is the scene load, `overhead` the per-part stages that do not divide
# (build_accel, trace_photons, tessellate, …), `render` the shade stage of the whole image.
# Also runs 1 process with 1 thread against 2 part processes with 1 thread each, at once.
#
# Usage: scripts/farm_scaling.sh [SCENE] [BINARY]   (defaults: cornell_box.ron, target/release/stagelight)
set -euo pipefail
cd "$(dirname "$0")/.."
scene="$(realpath "${1:-assets/scenes/cornell_box.ron}")"
bin="$(realpath "${2:-target/release/stagelight}")"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cd "$work"

now() { date +%s.%N; }
secs() { python3 -c "print(f'{$2 - $1:.3f}')"; }

t0=$(now); "$bin" check "$scene" >/dev/null; t1=$(now)
load=$(secs "$t0" "$t1")

"$bin" render "$scene" --threads 1 -o single.exr --stats-json single.json 2>/dev/null
t0=$(now); "$bin" render "$scene" --threads 1 -o single.exr 2>/dev/null; t1=$(now)
one=$(secs "$t0" "$t1")

t0=$(now)
"$bin" render "$scene" --threads 1 --part 1/2 -o p1.exr 2>/dev/null &
a=$!
"$bin" render "$scene" --threads 1 --part 2/2 -o p2.exr --stats-json p2.json 2>/dev/null &
b=$!
wait $a $b
t1=$(now)
"$bin" merge p1.exr p2.exr -o merged2.exr 2>/dev/null
t2=$(now)
two=$(secs "$t0" "$t1")
merge2=$(secs "$t1" "$t2")
cmp -s single.exr merged2.exr || { echo "merged image differs" >&2; exit 1; }

for k in 1 2 3 4 5 6 7 8; do
    "$bin" render "$scene" --threads 1 --part "$k/8" -o "q$k.exr" 2>/dev/null
done
t0=$(now); "$bin" merge q*.exr -o merged8.exr 2>/dev/null; t1=$(now)
merge8=$(secs "$t0" "$t1")
cmp -s single.exr merged8.exr || { echo "merged image differs" >&2; exit 1; }

python3 - "$load" "$one" "$two" "$merge2" "$merge8" single.json <<'EOF'
import json, sys
load, one, two, merge2, merge8 = map(float, sys.argv[1:6])
stages = {s["stage"]: s["seconds"] for s in json.load(open(sys.argv[6]))["stages"] if s["ran"]}
render = stages.get("shade", 0.0)
overhead = sum(v for k, v in stages.items() if k not in ("shade", "write_output"))
per_part_merge = max((merge8 - merge2) / 6, 0.0)
merge_fixed = max(merge2 - 2 * per_part_merge, 0.0)
print(f"scene load (check)            {load:8.3f} s")
print(f"per-part stages (not divided) {overhead:8.3f} s   {', '.join(f'{k} {v:.3f}' for k, v in stages.items() if k not in ('shade', 'write_output'))}")
print(f"shade, whole image, 1 thread  {render:8.3f} s")
print(f"merge: fixed {merge_fixed:.3f} s + {per_part_merge * 1000:.1f} ms per part (2 parts {merge2:.3f} s, 8 parts {merge8:.3f} s)")
print(f"1 process, 1 thread           {one:8.3f} s")
print(f"2 part processes at once      {two:8.3f} s  (+ merge {merge2:.3f} s): speedup {one / (two + merge2):.2f}x")
def t(n):
    return load + overhead + render / n + merge_fixed + per_part_merge * n
for n in (16, 64, 1000):
    print(f"model, {n:4d} nodes (1 thread each): {t(n):8.3f} s, speedup {t(1) / t(n):6.2f}x (limit {t(1) / (load + overhead + merge_fixed):.1f}x)")
EOF
