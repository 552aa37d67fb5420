#!/usr/bin/env bash
# Runs every fuzz target in fuzz/ for a fixed number of inputs (about half a minute each on a
# 2-vCPU host), starting from its corpus in fuzz/corpus/<target>, which is only read: the new
# inputs a run finds go to a scratch directory. A crash, a panic or a leak fails the script
# with libFuzzer's report and the reproducer's path (fuzz/artifacts/<target>/); add the
# reproducer to the corpus with the fix, so `tests/it/fuzz_corpus.rs` keeps it handled.
#
# Needs a nightly toolchain and cargo-fuzz (`cargo install cargo-fuzz --locked`).
# usage: scripts/fuzz_all.sh [TARGET ...]   env: FUZZ_SCALE (multiplies the input counts; 1)
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
# Inputs per target: its executions per second here (session 33) times about 30 s.
declare -A RUNS=(
    [scene_ron]=80000 [obj_text]=600000 [ply]=500000 [rib]=8000 [gltf]=300000
    [mi]=40000 [photon_map]=2000000 [mtl]=1000000 [png]=300000 [exr]=30000 [part_file]=30000
)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    mapfile -t targets < <(cargo +nightly fuzz list)
fi
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cargo +nightly fuzz build
for target in "${targets[@]}"; do
    runs=$((${RUNS[$target]:-100000} * ${FUZZ_SCALE:-1}))
    mkdir -p "$scratch/$target"
    log="$scratch/$target.log"
    if cargo +nightly fuzz run "$target" "$scratch/$target" "corpus/$target" -- \
        -seed=1 -runs="$runs" -max_total_time=$((120 * ${FUZZ_SCALE:-1})) >"$log" 2>&1; then
        echo "$target: $(grep -E '^Done [0-9]+ runs' "$log" | tail -1)"
    else
        tail -60 "$log" >&2
        echo "error: fuzz target $target failed (reproducer under fuzz/artifacts/$target/)" >&2
        exit 1
    fi
done
echo "fuzzing: ${#targets[@]} targets, no failure"
