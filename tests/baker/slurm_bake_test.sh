#!/usr/bin/env bash
# Sharded bakes on a real Slurm cluster (docs/scale-out.md): starts a single-node one with
# scripts/slurm-local.sh, runs scripts/slurm-bake.sh on the default room (4 shards, 2
# bounces: 3 job arrays, 3 merges, the asset job) and stops it again, whatever happens.
# Usage: slurm_bake_test.sh CASE PRT_BAKE WORK_DIR
#   identical  the asset equals the one-machine bake's bytes
#   requeue    a shard's prt-bake is killed (SIGKILL) mid-run; the job requeues itself, runs
#              again, and the asset still equals the one-machine bake's bytes
#   texels     a transfer-texture bake (--texels, 2 shards): the texel series runs in the same
#              jobs, and the asset equals the one-machine bake's bytes
#   failure    a bake that cannot finish (a shard's output path is a directory) fails with
#              --wait naming the shard, instead of hanging
set -euo pipefail
case_name=$1 bake=$2 work=$3
repo=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$work" && mkdir -p "$work" && cd "$work"
export SLURM_LOCAL_DIR=$work/slurm PRT_BAKE=$bake
# Ports of their own, so a cluster a developer started by hand (port 16817) is not in the way.
export SLURM_LOCAL_PORT=${SLURM_LOCAL_PORT:-16917}

fail() { echo "FAIL: $*" >&2; exit 1; }
# Waits up to $1 seconds for the command after it to succeed.
wait_for() {
  local seconds=$1
  shift
  for _ in $(seq 1 $((seconds * 5))); do "$@" && return 0; sleep 0.2; done
  return 1
}

trap '"$repo/scripts/slurm-local.sh" stop || true' EXIT
eval "$("$repo/scripts/slurm-local.sh" start)"
[[ -f $SLURM_CONF ]] || fail "slurm-local.sh start did not give SLURM_CONF"

options=(--order 3 --samples 64 --bounces 2)
timeout 300 "$bake" --default -o one.prt "${options[@]}" --quiet

case_identical() {
  timeout 600 "$repo/scripts/slurm-bake.sh" --default -o room.prt --shards 4 --wait "${options[@]}"
  cmp one.prt room.prt || fail "the Slurm bake differs from the one-machine bake"
  ls room.prt.shards/logs/pass2-shard3.log > /dev/null || fail "no log of the last pass's shards"
}

case_texels() {
  timeout 300 "$bake" --default -o one-texels.prt "${options[@]}" --texels --texture-size 64 --quiet
  timeout 600 "$repo/scripts/slurm-bake.sh" --default -o room.prt --shards 2 --wait "${options[@]}" --texels --texture-size 64
  cmp one-texels.prt room.prt || fail "the Slurm texel bake differs from the one-machine bake"
  ls room.prt.shards/plan.pass2.texels.shard1 > /dev/null || fail "no texel shard of the last pass"
}

job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1; }

case_requeue() {
  # Every write stalls 2 s before its rename, so the test can catch a shard mid-run.
  export PRT_TEST_STALL_BEFORE_RENAME_MS=2000
  final=$(timeout 300 "$repo/scripts/slurm-bake.sh" --default -o room.prt --shards 4 "${options[@]}" 2> submit.txt)
  cat submit.txt >&2
  array=$(sed -n 's/.*pass 1: job array \([0-9]*\).*/\1/p' submit.txt)
  [[ -n $array && -n $final ]] || fail "slurm-bake.sh did not report its jobs"
  log=room.prt.shards/logs/pass1-shard2.log
  wait_for 300 grep -q "stalling before renaming" "$log" 2> /dev/null || fail "shard 2 of pass 1 never reached its write"
  pid=$(pgrep -f -- "bake-shard --plan $work/room.prt.shards/plan --shard 2 --pass 1" | head -1)
  [[ -n $pid ]] || fail "no prt-bake process for shard 2 of pass 1"
  kill -KILL "$pid"
  echo "killed prt-bake (pid $pid) of shard 2 of pass 1" >&2
  wait_for 60 grep -q "requeueing job ${array}_2" "$log" || fail "the killed shard's job did not requeue itself"
  # Slurm holds a requeued job about two minutes before it may start again; start it now.
  wait_for 60 bash -c "scontrol show job ${array}_2 | grep -q 'JobState=PENDING'" || fail "the requeued shard is not pending"
  scontrol update JobId="${array}_2" StartTime=now
  wait_for 600 bash -c "[[ \$(scontrol show job $final | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p') =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT)$ ]]" ||
    fail "the asset job did not end in 600 s"
  [[ $(job_state "$final") == COMPLETED ]] || { tail -n 20 room.prt.shards/logs/*.log >&2; fail "the asset job ended $(job_state "$final")"; }
  scontrol show job "${array}_2" | grep -q "Restarts=1" || fail "shard 2 of pass 1 was not restarted once"
  cmp one.prt room.prt || fail "the Slurm bake with a requeued shard differs from the one-machine bake"
}

case_failure() {
  # Shard 1 of pass 1 cannot be written: its path is a directory (prt-bake exits 4, which
  # another try would not fix, so the job fails and the jobs after it are cancelled).
  mkdir -p room.prt.shards/plan.pass1.shard1
  status=0
  timeout 600 "$repo/scripts/slurm-bake.sh" --default -o room.prt --shards 4 --wait "${options[@]}" 2> submit.txt || status=$?
  cat submit.txt >&2
  ((status != 0)) || fail "slurm-bake.sh --wait succeeded on a bake that cannot finish"
  grep -q "the bake failed (asset job [0-9]*: CANCELLED" submit.txt || fail "slurm-bake.sh did not say the bake failed"
  grep -q "pass1-shard1.log:.*plan.pass1.shard1': exists and is a directory" submit.txt ||
    fail "slurm-bake.sh did not name the failed step's error"
  grep -q "plan.pass1.shard1.*is a directory\|plan.pass1.shard1.*directory" room.prt.shards/logs/pass1-shard1.log ||
    fail "the failed shard's log does not name its output"
  [[ ! -e room.prt ]] || fail "a failed bake wrote the asset"
}

"case_$case_name"
echo "PASS: $case_name"
