#!/usr/bin/env bash
# A prt-bake split over a Slurm cluster (docs/scale-out.md): plans the bake here, then
# submits one job array per pass (one task per shard) and one merge job after each, chained
# with --dependency=afterok, and a last job that merges every shard into the asset. The
# asset is byte for byte the one `prt-bake SCENE -o ASSET [options]` writes on one machine.
#
# Usage: scripts/slurm-bake.sh SCENE|--default -o ASSET --shards N [--work DIR] [--wait]
#                              [prt-bake options] [-- sbatch options]
#   --work DIR   where the plan, shards and logs go (default: ASSET.shards); it must be on a
#                filesystem every node sees, as must ASSET, SCENE and prt-bake
#   --wait       return when the asset is written (exit 0) or the bake failed (non-zero)
#   -- ...       passed to every sbatch (e.g. -- --partition=bake --cpus-per-task=8); each
#                step runs as many threads as its job has CPUs (--cpus-per-task, default 1)
# Environment: PRT_BAKE (the prt-bake to run; default: prt-bake on PATH, else
#   build/native/baker/prt-bake), PRT_SLURM_MAX_REQUEUES (times a killed step is requeued, default 3).
# Needs sbatch and scontrol (Slurm's client commands) on this host and on the nodes.
set -euo pipefail
# The whole script is one block, read before it runs: editing the file while a bake waits
# (--wait) cannot change what the running script does next.
{
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }
die() { echo "slurm-bake: error: $1" >&2; exit "${2:-2}"; }

root=$(cd "$(dirname "$0")/.." && pwd)
bake_args=() sbatch_opts=() asset="" shards="" work="" wait=0
while (($#)); do
  case $1 in
    -o | --output | --shards | --work) (($# >= 2)) || die "$1 needs a value" ;;&
    -o | --output) asset=$2; shift 2 ;;
    --shards) shards=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --wait) wait=1; shift ;;
    -h | --help) usage; exit 0 ;;
    --) shift; sbatch_opts=("$@"); break ;;
    *) bake_args+=("$1"); shift ;;
  esac
done
[[ -n $asset ]] || die "missing -o ASSET"
[[ $shards =~ ^[1-9][0-9]*$ ]] || die "--shards expects a whole number >= 1, got '${shards}'"
for c in sbatch scontrol; do command -v "$c" >/dev/null || die "$c not found: this host is not a Slurm client" 3; done

if [[ -n ${PRT_BAKE:-} ]]; then bake=$PRT_BAKE
elif command -v prt-bake >/dev/null; then bake=$(command -v prt-bake)
else bake=$root/build/native/baker/prt-bake
fi
[[ -x $bake ]] || die "prt-bake not found at '$bake' (set PRT_BAKE)" 3
bake=$(realpath "$bake")
asset_dir=$(dirname "$asset")
[[ -d $asset_dir ]] || die "the directory of '$asset' does not exist" 3
asset=$(realpath -m "$asset")
work=$(realpath -m "${work:-$asset.shards}")
created_work=0
[[ -e $work ]] || created_work=1
mkdir -p "$work/logs"
plan=$work/plan
max_requeues=${PRT_SLURM_MAX_REQUEUES:-3}

# The plan is made here, so a bad option or scene fails now, not in a job (and leaves no
# work directory behind it).
status=0
passes=$("$bake" plan "${bake_args[@]}" -o "$plan" --shards "$shards" --json | sed -n 's/.*"passes": \([0-9]*\).*/\1/p') || status=$?
if ((status != 0)) || [[ -z $passes ]]; then
  ((created_work)) && rm -rf "$work"
  die "prt-bake plan failed (status $status); nothing submitted" "$((status ? status : 5))"
fi

# One script for every step. It requeues its own job when prt-bake died of a signal (killed,
# preempted, out of memory) or of something another try may not meet (exit 6: a resource;
# 7: a service), at most max_requeues times; --requeue covers the node itself failing.
cat > "$work/job.sh" <<JOB
#!/bin/bash
# Written by scripts/slurm-bake.sh: one step of the sharded bake of $plan.
set -u
step=\$1 arg=\$2
# As many threads as the job was given CPUs (sbatch --cpus-per-task), not the node's count.
threads=\${SLURM_CPUS_PER_TASK:-1}
case \$step in
  shard) "$bake" bake-shard --plan "$plan" --shard "\$SLURM_ARRAY_TASK_ID" --pass "\$arg" --threads "\$threads" ;;
  merge) "$bake" merge --plan "$plan" --pass "\$arg" --threads "\$threads" ;;
  asset) "$bake" merge --plan "$plan" -o "\$arg" --threads "\$threads" ;;
esac
status=\$?
if (( status >= 128 || status == 6 || status == 7 )) && (( \${SLURM_RESTART_COUNT:-0} < $max_requeues )); then
  id=\${SLURM_ARRAY_JOB_ID:+\${SLURM_ARRAY_JOB_ID}_\${SLURM_ARRAY_TASK_ID}}
  id=\${id:-\$SLURM_JOB_ID}
  echo "slurm-bake: step \$step \$arg exited with status \$status; requeueing job \$id (restart \${SLURM_RESTART_COUNT:-0})" >&2
  # The requeue ends this run; the sleep only waits for that.
  scontrol requeue "\$id" && sleep 60
fi
exit \$status
JOB
chmod +x "$work/job.sh"

common=(--parsable --requeue --open-mode=append --kill-on-invalid-dep=yes "${sbatch_opts[@]}")
# submit VAR SBATCH-ARGS...: submits a job and sets VAR to its id. When sbatch fails, the
# jobs already submitted are cancelled: half a chain would only wait or fail later.
submitted=()
submit() {
  local var=$1 id
  shift
  if ! id=$(sbatch "${common[@]}" "$@"); then
    ((${#submitted[@]})) && scancel "${submitted[@]}" 2>/dev/null
    die "sbatch failed; cancelled the ${#submitted[@]} jobs already submitted" 7
  fi
  submitted+=("${id%%;*}")
  printf -v "$var" '%s' "${id%%;*}"
}

dependency=()
for ((k = 0; k < passes; k++)); do
  submit array "${dependency[@]}" --job-name="prt-bake-pass$k" --array="0-$((shards - 1))" \
               --output="$work/logs/pass$k-shard%a.log" "$work/job.sh" shard "$k"
  submit merge --dependency="afterok:$array" --job-name="prt-bake-merge$k" \
               --output="$work/logs/pass$k-merge.log" "$work/job.sh" merge "$k"
  echo "slurm-bake: pass $k: job array $array ($shards shards), merge job $merge" >&2
  dependency=(--dependency="afterok:$merge")
done
final_opts=("${dependency[@]}" --job-name=prt-bake-asset --output="$work/logs/asset.log")
if ((wait)); then
  echo "slurm-bake: waiting for the asset job (logs: $work/logs)" >&2
  status=0
  final=$(sbatch "${common[@]}" --wait "${final_opts[@]}" "$work/job.sh" asset "$asset") || status=$?
  final=${final%%;*}
  # sbatch --wait exits 0 for a job cancelled before it ran (a failed step cancels the jobs
  # after it), so the job's own state decides.
  state=$(scontrol show job "$final" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1)
  if ((status != 0)) || [[ $state != COMPLETED || ! -f $asset ]]; then
    # The first error of each failed step, with its log.
    grep -H "error:" "$work"/logs/*.log 2>/dev/null | head -n 10 | sed 's/^/slurm-bake: /' >&2 || true
    die "the bake failed (asset job ${final:-?}: ${state:-unknown}, sbatch status $status); see the logs in $work/logs" 4
  fi
  echo "slurm-bake: wrote $asset" >&2
else
  submit final "${final_opts[@]}" "$work/job.sh" asset "$asset"
  echo "slurm-bake: asset job $final writes $asset (logs: $work/logs)" >&2
  echo "$final"
fi
exit
}
