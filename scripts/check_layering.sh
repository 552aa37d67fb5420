#!/usr/bin/env bash
# Layering checks for src/ (called from .ci/run):
#   1. components/ is plain data: no file under src/components/ names anything in the crate
#      outside components (`crate::X` with X ≠ components, or `super::super`) in code;
#      comments (doc links included) may mention other modules;
#   2. no import cycle between the top-level modules of src/, nor between the child modules
#      of one top-level module (scripts/module_cycles.py).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== layering: src/components/ imports nothing else from the crate"
if grep -rn --include='*.rs' -E 'crate::|super::super' src/components \
    | grep -v -E '^src/[^:]+:[0-9]+:\s*(//|\*)' \
    | grep -v -E 'crate::components(::|\b)'; then
    echo "error: src/components/ must not use the rest of the crate (plain data only)" >&2
    exit 1
fi

echo "== layering: import cycles between modules of src/"
python3 scripts/module_cycles.py src
