#!/usr/bin/env bash
# A/B timing of stagelight binaries, stage by stage, on one scene. The binaries run in
# alternated rounds (A B C, A B C, …), so a change in the host's load hits each alike; each
# run's `--stats` stage seconds are collected, and per binary and stage the median, the
# least and the largest are printed (medians of alternated rounds are what
# docs/ray-layer.md quotes: this host's rounds spread 10–40 % in busy minutes). Every run's
# output is compared with the first binary's first output: same bytes or not.
#
# usage: scripts/stage_ab.sh SCENE ROUNDS BIN [BIN ...]
#   env: THREADS (default 1), ARGS (extra render arguments, e.g. "--integrator path --spp 16"),
#        OUT_DIR (where outputs go; a temporary directory by default)
# example: scripts/stage_ab.sh assets/scenes/caustics.ron 8 ./old/stagelight target/release/stagelight
set -euo pipefail
if [ $# -lt 3 ]; then
    echo "usage: $0 SCENE ROUNDS BIN [BIN ...]" >&2
    exit 2
fi
SCENE=$1
ROUNDS=$2
shift 2
BINS=("$@")
[ -f "$SCENE" ] || { echo "error: no scene file '$SCENE'" >&2; exit 2; }
[[ "$ROUNDS" =~ ^[1-9][0-9]*$ ]] || { echo "error: ROUNDS must be a positive integer, got '$ROUNDS'" >&2; exit 2; }
for b in "${BINS[@]}"; do
    [ -x "$b" ] || { echo "error: '$b' is not an executable stagelight binary" >&2; exit 2; }
done
DIR=${OUT_DIR:-$(mktemp -d)}
mkdir -p "$DIR"
THREADS=${THREADS:-1}
TIMES="$DIR/stage_times.txt"
: > "$TIMES"
first=""
same=1
for r in $(seq "$ROUNDS"); do
    for i in "${!BINS[@]}"; do
        out="$DIR/out_${i}_${r}.exr"
        # shellcheck disable=SC2086
        if ! stats=$("${BINS[$i]}" render "$SCENE" --threads "$THREADS" --stats -o "$out" ${ARGS:-} 2>&1); then
            echo "error: ${BINS[$i]} failed on $SCENE:" >&2
            echo "$stats" | tail -5 >&2
            exit 1
        fi
        echo "$stats" | awk -v bin="$i" '$2 == "yes" { print bin, $1, $3 } $1 == "total" { print bin, "total", $2 }' >> "$TIMES"
        if [ -z "$first" ]; then
            first=$out
        elif ! cmp -s "$first" "$out"; then
            same=0
            echo "differs: ${BINS[$i]} round $r ($out) against $first"
        fi
    done
done
echo "scene $SCENE, $ROUNDS alternated rounds, $THREADS thread(s); seconds per stage: median [least, largest]"
for i in "${!BINS[@]}"; do
    echo "$i: ${BINS[$i]}"
    awk -v bin="$i" '$1 == bin { print $2, $3 }' "$TIMES" | sort -k1,1 -k2,2g | awk '
        { v[$1] = v[$1] " " $2; n[$1]++ }
        END {
            for (s in v) {
                split(substr(v[s], 2), a, " ")
                k = n[s]
                med = (k % 2) ? a[(k + 1) / 2] : (a[k / 2] + a[k / 2 + 1]) / 2
                printf "   %-16s %.4f [%.4f, %.4f]\n", s, med, a[1], a[k]
            }
        }' | sort
done
if [ "$same" = 1 ]; then
    echo "outputs: every run's bytes equal the first's"
else
    echo "outputs: some runs differ (listed above)"
fi
