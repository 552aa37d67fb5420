#!/usr/bin/env bash
# Renders (and bakes) every example scene with the current tree and with BASE_REV, and
# compares the output files byte for byte. Exit 0 when every file is identical.
#
#   scripts/compare_assets.sh BASE_REV [SCENE...]
#   BASE_BIN=/path/to/old/stagelight HEAD_BIN=/path/to/new/stagelight \
#       scripts/compare_assets.sh BASE_REV                     (skip building either)
#
# Builds both with PROFILE (default release; PROFILE=dev for the test profile), BASE_REV in a
# temporary git worktree with its own target dir under target/compare-base so repeated runs
# reuse it. The working tree builds into CARGO_TARGET_DIR (default target/). Outputs go to
# target/compare/{base,head}/.
set -euo pipefail
cd "$(dirname "$0")/.."
base_rev=${1:?usage: scripts/compare_assets.sh BASE_REV [SCENE...]}
shift
root=$(pwd)
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
    mapfile -t scenes < <(ls assets/scenes/*.ron)
fi

profile=${PROFILE:-release}
dir_of_profile=$([ "$profile" = dev ] && echo debug || echo "$profile")
head_target=${CARGO_TARGET_DIR:-$root/target}
base_bin=${BASE_BIN:-}
if [ -z "$base_bin" ]; then
    base_tree=$(mktemp -d /tmp/stagelight-base.XXXXXX)
    trap 'git worktree remove --force "$base_tree" >/dev/null 2>&1 || true' EXIT
    git worktree add --detach -q "$base_tree" "$base_rev"
    echo "== building $base_rev ($profile)"
    (cd "$base_tree" && cargo build --profile "$profile" -q --target-dir "$root/target/compare-base")
    base_bin="$root/target/compare-base/$dir_of_profile/stagelight"
fi
head_bin=${HEAD_BIN:-}
if [ -z "$head_bin" ]; then
    echo "== building the working tree ($profile)"
    cargo build --profile "$profile" -q
    head_bin="$head_target/$dir_of_profile/stagelight"
fi

out="$root/target/compare"
rm -rf "$out"
mkdir -p "$out/base" "$out/head"

render() { # bin dir scene
    local bin=$1 dir=$2 scene=$3 name
    name=$(basename "$scene" .ron)
    mkdir -p "$dir/$name"
    # Outputs are relative to the working directory; bakes go to the same directory.
    (cd "$dir/$name" && "$bin" render "$root/$scene" --bake --threads 2 >/dev/null 2>"$dir/$name.log" \
        || "$bin" render "$root/$scene" --threads 2 >/dev/null 2>>"$dir/$name.log") \
        || echo "render failed: $scene (see $dir/$name.log)"
}

identical=0
different=0
for scene in "${scenes[@]}"; do
    render "$base_bin" "$out/base" "$scene"
    render "$head_bin" "$out/head" "$scene"
    name=$(basename "$scene" .ron)
    files=$(cd "$out/base/$name" && find . -type f | sort)
    head_files=$(cd "$out/head/$name" && find . -type f | sort)
    if [ "$files" != "$head_files" ]; then
        echo "DIFFERENT file lists: $scene"
        different=$((different + 1))
        continue
    fi
    if [ -z "$files" ]; then
        echo "no outputs: $scene"
        continue
    fi
    for f in $files; do
        if cmp -s "$out/base/$name/$f" "$out/head/$name/$f"; then
            echo "identical  $name/${f#./}"
            identical=$((identical + 1))
        else
            echo "DIFFERENT  $name/${f#./}"
            different=$((different + 1))
        fi
    done
done
echo "$identical identical, $different different (base $base_rev)"
[ "$different" -eq 0 ]
