#!/bin/bash
# Submit an Iris render to a Slurm cluster: an array job (one task per shard or frame),
# then the job that assembles the result, started only if every task succeeded
# (--dependency=afterok). Slurm is the scheduler: Iris only renders its share and merges.
#
#   scripts/slurm/submit.sh render    SCENE OUTDIR SHARDS [iris render flags...]
#       -> OUTDIR/part_I.exr (I = 1..SHARDS), then OUTDIR/<scene>.exr and .png (iris merge)
#   scripts/slurm/submit.sh turntable SCENE OUTDIR FRAMES [iris turntable flags...]
#       -> OUTDIR/frame_*.png (one task per frame), then the animation (--assemble)
#
# Environment: IRIS (the iris binary, default target/release/iris: it must be on a path
# every node sees, as must SCENE and OUTDIR), CPUS (cores per task, default 2),
# SBATCH_ARGS (extra sbatch options: partition, time limit, account...).
# Prints the two job ids ("array ID", "final ID"); `squeue`, `sacct` and the
# OUTDIR/*.log files follow them. A failed task: rerun it with
#   IRIS=... IRIS_SCENE=... IRIS_OUT=... IRIS_SHARDS=... sbatch --array=I scripts/slurm/iris-shard.sbatch FLAGS
# then submit scripts/slurm/iris-merge.sbatch again.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 4 ] || usage
kind=$1 scene=$2 out=$3 count=$4
shift 4
case "$count" in ''|*[!0-9]*) echo "submit.sh: the count must be a positive integer, got '$count'" >&2; exit 2;; esac
[ "$count" -ge 1 ] || { echo "submit.sh: the count must be at least 1" >&2; exit 2; }
[ -f "$scene" ] || { echo "submit.sh: scene $scene not found" >&2; exit 2; }
iris=$(realpath "${IRIS:-$here/../../target/release/iris}")
[ -x "$iris" ] || { echo "submit.sh: iris binary $iris not found (build it, or set IRIS)" >&2; exit 2; }
mkdir -p "$out"
export IRIS="$iris" IRIS_SCENE="$(realpath "$scene")" IRIS_OUT="$(realpath "$out")"
name=$(basename "${scene%.*}")
cpus=${CPUS:-2}
# shellcheck disable=SC2086
common=(--parsable --export=ALL --chdir="$IRIS_OUT" --cpus-per-task="$cpus" ${SBATCH_ARGS:-})
case "$kind" in
    render)
        export IRIS_SHARDS="$count" IRIS_NAME="$name"
        array=$(sbatch "${common[@]}" --array="1-$count" "$here/iris-shard.sbatch" "$@")
        array=${array%%;*}
        final=$(sbatch "${common[@]}" --dependency="afterok:$array" "$here/iris-merge.sbatch")
        ;;
    turntable)
        export IRIS_FRAMES="$count"
        array=$(sbatch "${common[@]}" --array="0-$((count - 1))" "$here/iris-frame.sbatch" "$@")
        array=${array%%;*}
        final=$(sbatch "${common[@]}" --dependency="afterok:$array" "$here/iris-assemble.sbatch" "$@")
        ;;
    *) usage ;;
esac
echo "array $array"
echo "final $final"
