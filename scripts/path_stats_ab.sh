#!/bin/bash
# Statistical A/B of two stagelight binaries' path tracers, for changes that alter the last
# bits of images (issue 17: "equal up to floating-point reassociation"). For each scene: a
# converged reference from BASE (REF_SPP samples, a seed the test renders never use), then
# BASE and NEW at SPP samples with seeds 1..SEEDS; prints relMSE against the reference for
# both (equal within noise when NEW is unbiased and as noisy), and per channel the mean
# difference NEW − BASE over the image as a Z-score against the per-pixel noise
# (std of BASE − reference over √pixels); |Z| < 3 passes.
#
# usage: scripts/path_stats_ab.sh BASE NEW [SPP=16] [REF_SPP=1024] [SEEDS=4] [scene.ron ...]
# (scenes default to cornell_box glass textures area_lights environment; one thread each so
# the renders are also each binary's deterministic single-thread output)
set -euo pipefail
BASE=$1; NEW=$2; SPP=${3:-16}; REF_SPP=${4:-1024}; SEEDS=${5:-4}
shift $(( $# < 5 ? $# : 5 ))
SCENES=("$@")
[ ${#SCENES[@]} -gt 0 ] || SCENES=(cornell_box.ron glass.ron textures.ron area_lights.ron environment.ron)
HERE=$(cd "$(dirname "$0")" && pwd)
DIR=${OUT_DIR:-$(mktemp -d)}
mkdir -p "$DIR"
THREADS=${THREADS:-2}
fail=0
for s in "${SCENES[@]}"; do
  n=${s%.ron}
  ref="$DIR/${n}_ref${REF_SPP}.exr"
  [ -f "$ref" ] || "$BASE" render "$HERE/../assets/scenes/$s" --integrator path --spp "$REF_SPP" \
      --seed 987654 --threads "$THREADS" -o "$ref" >/dev/null 2>&1
  for k in $(seq "$SEEDS"); do
    "$BASE" render "$HERE/../assets/scenes/$s" --integrator path --spp "$SPP" --seed "$k" \
        --threads 1 -o "$DIR/${n}_base_$k.exr" >/dev/null 2>&1
    "$NEW" render "$HERE/../assets/scenes/$s" --integrator path --spp "$SPP" --seed "$k" \
        --threads 1 -o "$DIR/${n}_new_$k.exr" >/dev/null 2>&1
  done
  python3 "$HERE/path_stats_compare.py" "$DIR" "$n" "$REF_SPP" "$SEEDS" || fail=1
done
exit $fail
