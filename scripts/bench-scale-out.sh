#!/usr/bin/env bash
# What sharding costs and what it could gain (docs/bench/scale-out.md): bakes SCENE (or the
# default room) on one machine, then the same plan with N shards, every shard run here one
# after another, timing each step. The one-machine time against "critical path" (per pass the
# slowest shard plus its merge, plus the asset merge) is the speed-up N machines could reach
# with no queueing; "total" against the one-machine time is the overhead of sharding.
# Usage: scripts/bench-scale-out.sh [--shards N] [SCENE|--default] [prt-bake options]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bake=${PRT_BAKE:-$root/build/native/baker/prt-bake}
shards=4
if [[ ${1:-} == --shards ]]; then shards=$2; shift 2; fi
(($#)) || set -- --default
work=$(mktemp -d "${TMPDIR:-/tmp}/prt-bench-scale-out-XXXXXX")
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
# Arithmetic on decimals with awk (part of every Debian system).
calc() { awk "BEGIN { print $1 }"; }
since() { calc "$(now) - $1"; }

t0=$(now)
"$bake" "$@" -o "$work/one.prt" --quiet
one=$(since "$t0")

t0=$(now)
passes=$("$bake" plan "$@" -o "$work/p.plan" --shards "$shards" --json --quiet | sed -n 's/.*"passes": \([0-9]*\).*/\1/p')
plan_s=$(since "$t0")
total=$plan_s critical=$plan_s
rows=""
for ((k = 0; k < passes; k++)); do
  slowest=0 sum=0
  for ((i = 0; i < shards; i++)); do
    t0=$(now)
    "$bake" bake-shard --plan "$work/p.plan" --shard "$i" --pass "$k" --quiet
    s=$(since "$t0")
    sum=$(calc "$sum + $s")
    slowest=$(calc "($s > $slowest) ? $s : $slowest")
  done
  t0=$(now)
  "$bake" merge --plan "$work/p.plan" --pass "$k" --quiet
  m=$(since "$t0")
  total=$(calc "$total + $sum + $m")
  critical=$(calc "$critical + $slowest + $m")
  rows+=$(printf '| %d | %.2f | %.2f | %.2f |\n' "$k" "$sum" "$slowest" "$m")$'\n'
done
t0=$(now)
"$bake" merge --plan "$work/p.plan" -o "$work/sharded.prt" --quiet
final=$(since "$t0")
total=$(calc "$total + $final")
critical=$(calc "$critical + $final")
cmp "$work/one.prt" "$work/sharded.prt" || { echo "bench-scale-out: the sharded asset differs" >&2; exit 1; }
bytes=$(du -sb "$work" | cut -f1)

echo "prt-bake $* ; $shards shards, $passes passes planned; $(nproc) cores"
echo
echo "| pass | shards, summed (s) | slowest shard (s) | merge (s) |"
echo "|---|---|---|---|"
printf '%s' "$rows"
printf '\none machine: %.2f s; sharded, every step here in turn: %.2f s (%.2fx); plan %.2f s, asset merge %.2f s\n' \
  "$one" "$total" "$(calc "$total / $one")" "$plan_s" "$final"
printf 'critical path with %d machines (no queueing): %.2f s, a speed-up of %.2fx; work files %.1f MB; assets identical\n' \
  "$shards" "$critical" "$(calc "$one / $critical")" "$(calc "$bytes / 1000000")"
