#!/bin/sh
# Writes a Slurm job array that runs a sweep in N shards, and the job that
# merges them when all are done (docs/studies.md):
#
#   sh tools/slurm-sweep.sh SWEEP_FILE OUT_DIR N [CPUS_PER_TASK] > sweep.sbatch
#   jobid=$(sbatch --parsable sweep.sbatch)
#   sbatch --dependency=afterok:$jobid --wrap "$(sh tools/slurm-sweep.sh --merge OUT_DIR N)"
#
# Each array task runs `uuvsim sweep SWEEP_FILE --out OUT_DIR/shard-K --shard K/N
# -j CPUS_PER_TASK`; a task that is requeued resumes its shard. UUVSIM names
# the program (default: uuvsim on the PATH).
set -u
uuvsim=${UUVSIM:-uuvsim}
if [ "${1:-}" = --merge ]; then
    [ $# -eq 3 ] || { echo "usage: slurm-sweep.sh --merge OUT_DIR N" >&2; exit 2; }
    out=$2; n=$3
    parts=""
    k=1
    while [ "$k" -le "$n" ]; do parts="$parts $out/shard-$k"; k=$((k + 1)); done
    echo "$uuvsim sweep-merge --out $out/merged$parts"
    exit 0
fi
if [ $# -lt 3 ] || [ $# -gt 4 ]; then
    echo "usage: slurm-sweep.sh SWEEP_FILE OUT_DIR N [CPUS_PER_TASK]" >&2
    exit 2
fi
sweep=$1; out=$2; n=$3; cpus=${4:-1}
case "$n$cpus" in
    *[!0-9]*) echo "slurm-sweep: N and CPUS_PER_TASK must be whole numbers" >&2; exit 2 ;;
esac
[ "$n" -ge 1 ] && [ "$cpus" -ge 1 ] || { echo "slurm-sweep: N and CPUS_PER_TASK must be >= 1" >&2; exit 2; }
[ -f "$sweep" ] || { echo "slurm-sweep: $sweep: no such file" >&2; exit 2; }
cat <<JOB
#!/bin/sh
#SBATCH --job-name=uuvsim-sweep
#SBATCH --array=1-$n
#SBATCH --cpus-per-task=$cpus
#SBATCH --output=$out/slurm-%A_%a.log
#SBATCH --requeue
mkdir -p "$out"
exec $uuvsim sweep "$sweep" --out "$out/shard-\$SLURM_ARRAY_TASK_ID" \\
    --shard "\$SLURM_ARRAY_TASK_ID/$n" -j "\${SLURM_CPUS_PER_TASK:-$cpus}"
JOB
