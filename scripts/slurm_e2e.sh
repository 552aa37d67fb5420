#!/usr/bin/env bash
# A real Slurm run of a farm render on this machine: brings up a single-node Slurm
# (munge, slurmctld and slurmd on localhost, a generated slurm.conf in a temporary
# directory), submits `stagelight farm SCENE --parts 4 --submit`, waits for the merge job
# and compares its image with a local render byte for byte; then the same for a bake
# (`stagelight farm BAKE --bake --parts 3 --submit` against a local bake) and a photon-mapped
# render whose photon job runs before its array; tears everything
# down after.
#
# Usage: scripts/slurm_e2e.sh [STAGELIGHT_BINARY]   (default: target/release/stagelight)
# Needs root to start the daemons; installs Debian's slurm-wlm and munge when missing.
# Exits non-zero, loudly, when Slurm cannot be installed or started: it never passes
# without having run the job.
set -euo pipefail
cd "$(dirname "$0")/.."
bin="$(realpath "${1:-target/release/stagelight}")"
[ -x "$bin" ] || { echo "slurm_e2e: no stagelight binary at $bin" >&2; exit 1; }

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    echo "slurm_e2e: installing slurm-wlm and munge"
    if ! DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
        slurm-wlm munge >/dev/null; then
        echo "slurm_e2e: FAILED: cannot install slurm-wlm/munge; the Slurm test did NOT run" >&2
        exit 1
    fi
fi

work="$(mktemp -d /tmp/stagelight-slurm.XXXXXX)"
chmod 755 "$work"
host="$(hostname -s)"
pids=()
started_munge=
cleanup() {
    set +e
    scancel --full --quiet -u root >/dev/null 2>&1
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
    sleep 1
    for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
    [ -n "${started_munge:-}" ] && pkill -x munged
    rm -rf "$work"
}
trap cleanup EXIT

# munge, as Debian installs it (key in /etc/munge), started by hand when not running.
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    [ -f /etc/munge/munge.key ] || runuser -u munge -- mungekey --create
    mkdir -p /run/munge /var/log/munge /var/lib/munge
    chown munge:munge /run/munge /var/log/munge /var/lib/munge
    runuser -u munge -- /usr/sbin/munged
    sleep 0.5
    started_munge=1
fi
if ! munge -n | unmunge >/dev/null; then
    echo "slurm_e2e: FAILED: munge does not work; the Slurm test did NOT run" >&2
    exit 1
fi

cpus="$(nproc)"
mem_mb="$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 / 2 ))"
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<EOF
ClusterName=stagelight-ci
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
SchedulerType=sched/backfill
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldPort=16817
SlurmdPort=16818
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
DefMemPerCPU=256
NodeName=$host CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=ci Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$work/slurm.conf"

slurmctld -i -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N "$host"
sleep 1
[ -f "$work/slurmctld.pid" ] && pids+=("$(cat "$work/slurmctld.pid")")
[ -f "$work/slurmd.pid" ] && pids+=("$(cat "$work/slurmd.pid")")

for _ in $(seq 1 60); do
    if sinfo -h -o '%T' 2>/dev/null | grep -qE '^idle'; then break; fi
    sleep 1
done
if ! sinfo -h -o '%T' | grep -qE '^idle'; then
    echo "slurm_e2e: FAILED: the Slurm node did not come up; the Slurm test did NOT run" >&2
    sinfo >&2 || true
    tail -20 "$work/slurmctld.log" "$work/slurmd.log" >&2 || true
    exit 1
fi
echo "slurm_e2e: single-node Slurm up ($host, $cpus CPUs)"

scene="$(realpath assets/scenes/cornell_box.ron)"
caustics="$(realpath assets/scenes/caustics.ron)"
mkdir -p "$work/run"
chmod 777 "$work/run"
cd "$work/run"
"$bin" render "$scene" --spp 4 -o local.png 2>/dev/null
submitted="$("$bin" farm "$scene" --parts 4 --spp 4 --out "$work/run/job" -o "$work/run/farm.png" \
    --cpus-per-task 1 --submit)"
echo "$submitted"
merge_id="$(echo "$submitted" | awk '/^merge job/ {print $3}')"
[ -n "$merge_id" ] || { echo "slurm_e2e: FAILED: no merge job id" >&2; exit 1; }

wait_for() {
    for _ in $(seq 1 600); do
        if [ -z "$(squeue -h -j "$1" 2>/dev/null)" ]; then break; fi
        sleep 1
    done
}
wait_for "$merge_id"
if [ ! -f farm.png ]; then
    echo "slurm_e2e: FAILED: the merge job wrote no image" >&2
    tail -n 20 job/logs/*.log >&2 || true
    exit 1
fi
if cmp -s local.png farm.png; then
    echo "slurm_e2e: ok: 4 Slurm array parts merged byte-identical to the local render"
else
    echo "slurm_e2e: FAILED: the farm image differs from the local render" >&2
    exit 1
fi

# Photon maps through the farm: a photon job traces them once, the parts load them.
"$bin" render "$caustics" --spp 1 -o local_caustics.png 2>/dev/null
submitted="$("$bin" farm "$caustics" --parts 3 --spp 1 --out "$work/run/caustics_job" \
    -o "$work/run/farm_caustics.png" --cpus-per-task 1 --submit)"
echo "$submitted"
echo "$submitted" | grep -q '^photon job ' || { echo "slurm_e2e: FAILED: no photon job" >&2; exit 1; }
merge_id="$(echo "$submitted" | awk '/^merge job/ {print $3}')"
[ -n "$merge_id" ] || { echo "slurm_e2e: FAILED: no caustics merge job id" >&2; exit 1; }
wait_for "$merge_id"
if [ ! -f farm_caustics.png ] || ! cmp -s local_caustics.png farm_caustics.png; then
    echo "slurm_e2e: FAILED: the farm caustics render differs from the local render (or is missing)" >&2
    tail -n 20 caustics_job/logs/*.log >&2 || true
    exit 1
fi
maps="$(ls caustics_job/photons | wc -l)"
[ "$maps" = 1 ] || { echo "slurm_e2e: FAILED: $maps photon map files, expected 1" >&2; exit 1; }
echo "slurm_e2e: ok: photon job + 3 Slurm parts loading its map merged byte-identical to the local render"

# A bake through the farm: a floor with an occluding block, two requests' worth of files.
cat >bake.ron <<'SCENE'
Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (8, 8),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)))],
    lights: [(name: "sun", kind: Directional(direction: (0.3, 0.2, -1)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [
        (name: "floor", mesh: Inline(
            vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
        (name: "block", mesh: Inline(
            vertices: [(-0.3, -0.3, 0.4), (0.3, -0.3, 0.4), (0.3, 0.3, 0.4), (-0.3, 0.3, 0.4)],
            uvs: [(0, 0), (1, 0), (1, 1), (0, 1)],
            polygons: [[0, 1, 2, 3]]), material: "grey"),
    ],
    instances: [
        (name: "floor_1", of: "floor", bake: (resolution: (64, 64), uvs: Mesh, mask: true,
            outputs: [(kind: AmbientOcclusion(samples: 16, bent_normals: true))])),
        (name: "block_1", of: "block", bake: (resolution: (32, 32), uvs: Mesh,
            outputs: [(kind: Lightmap(), format: Png8)])),
    ],
    groups: [(name: "world", members: ["floor_1", "block_1"])],
    render: (root: "world", camera: "cam"),
)
SCENE
"$bin" bake bake.ron -o local_bake 2>/dev/null
submitted="$("$bin" farm bake.ron --bake --parts 3 --out "$work/run/bake_job" \
    -o "$work/run/farm_bake" --cpus-per-task 1 --submit)"
echo "$submitted"
merge_id="$(echo "$submitted" | awk '/^merge job/ {print $3}')"
[ -n "$merge_id" ] || { echo "slurm_e2e: FAILED: no bake merge job id" >&2; exit 1; }
wait_for "$merge_id"
if [ ! -d farm_bake ] || ! diff -r local_bake farm_bake >/dev/null; then
    echo "slurm_e2e: FAILED: the farm bake differs from the local bake (or is missing)" >&2
    tail -n 20 bake_job/logs/*.log >&2 || true
    exit 1
fi
echo "slurm_e2e: ok: 3 Slurm bake parts merged byte-identical to the local bake ($(ls farm_bake | wc -l) files)"
