#!/usr/bin/env bash
# What sharding costs and what it could gain (docs/bench/scale-out.md): bakes SCENE (or the
# default room) on one machine, then the same plan with N shards, every shard run here one
# after another, timing each step. The one-machine time against "critical path" (per pass the
# slowest shard plus its merge, plus the asset merge) is the speed-up N machines could reach
# with no queueing; "total" against the one-machine time is the overhead of sharding.
# Every step is timed twice: wall clock, and CPU (user + system, from /usr/bin/time), which a
# machine shared with other work disturbs far less, so overheads are given in CPU time too.
# Works for texel bakes (--texels) too: their texel files are counted apart.
# --json FILE also writes the numbers as one JSON object (docs/bench/scale-out.json holds runs).
# Usage: scripts/bench-scale-out.sh [--shards N] [--json FILE] [SCENE|--default] [prt-bake options]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bake=${PRT_BAKE:-$root/build/native/baker/prt-bake}
shards=4 json=""
while [[ ${1:-} == --shards || ${1:-} == --json ]]; do
  if [[ $1 == --shards ]]; then shards=$2; else json=$2; fi
  shift 2
done
(($#)) || set -- --default
[[ -x /usr/bin/time ]] || { echo "bench-scale-out: needs /usr/bin/time (Debian package time)" >&2; exit 3; }
work=$(mktemp -d "${TMPDIR:-/tmp}/prt-bench-scale-out-XXXXXX")
trap 'rm -rf "$work"' EXIT

# Arithmetic on decimals with awk (part of every Debian system).
calc() { awk "BEGIN { print $1 }"; }
# timed CMD...: runs CMD (stdout kept in $work/out.txt), sets $wall and $cpu (seconds).
timed() {
  /usr/bin/time -f '%e %U %S' -o "$work/time.txt" "$@" > "$work/out.txt"
  read -r wall user sys < "$work/time.txt"
  cpu=$(calc "$user + $sys")
}

timed "$bake" "$@" -o "$work/one.prt" --quiet
one=$wall one_cpu=$cpu

timed "$bake" plan "$@" -o "$work/p.plan" --shards "$shards" --json --quiet
passes=$(sed -n 's/.*"passes": \([0-9]*\).*/\1/p' "$work/out.txt")
plan_s=$wall plan_cpu=$cpu
total=$plan_s critical=$plan_s total_cpu=$plan_cpu
rows="" json_passes=""
for ((k = 0; k < passes; k++)); do
  slowest=0 sum=0 sum_cpu=0
  for ((i = 0; i < shards; i++)); do
    timed "$bake" bake-shard --plan "$work/p.plan" --shard "$i" --pass "$k" --quiet
    sum=$(calc "$sum + $wall")
    sum_cpu=$(calc "$sum_cpu + $cpu")
    slowest=$(calc "($wall > $slowest) ? $wall : $slowest")
  done
  timed "$bake" merge --plan "$work/p.plan" --pass "$k" --quiet
  total=$(calc "$total + $sum + $wall")
  total_cpu=$(calc "$total_cpu + $sum_cpu + $cpu")
  critical=$(calc "$critical + $slowest + $wall")
  rows+=$(printf '| %d | %.2f | %.2f | %.2f | %.2f | %.2f |\n' "$k" "$sum" "$slowest" "$wall" "$sum_cpu" "$cpu")$'\n'
  json_passes+=$(printf '%s{"pass": %d, "shards_s": %.3f, "slowest_s": %.3f, "merge_s": %.3f, "shards_cpu_s": %.3f, "merge_cpu_s": %.3f}' \
    "${json_passes:+, }" "$k" "$sum" "$slowest" "$wall" "$sum_cpu" "$cpu")
done
timed "$bake" merge --plan "$work/p.plan" -o "$work/sharded.prt" --quiet
final=$wall final_cpu=$cpu
total=$(calc "$total + $final")
total_cpu=$(calc "$total_cpu + $final_cpu")
critical=$(calc "$critical + $final")
cmp "$work/one.prt" "$work/sharded.prt" || { echo "bench-scale-out: the sharded asset differs" >&2; exit 1; }
bytes=$(du -sb "$work" | cut -f1)
# Bytes of each kind of work file (the assets excluded).
kind_bytes() { find "$work" -name "$1" -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }'; }
# The vertex series' files (a texel plan's texel files, PLAN.passK.texels.*, match the same globs).
vertex_bytes() { find "$work" -name "$1" ! -name '*.texels.*' -printf '%s\n' | awk '{ s += $1 } END { print s + 0 }'; }
direct_bytes=$(vertex_bytes 'p.plan.pass0.shard*') merged_bytes=$(vertex_bytes 'p.plan.pass*.merged')
bounce_bytes=$(calc "$(vertex_bytes 'p.plan.pass*.shard*') - $direct_bytes")
# A texel plan's texel series (--texels): its shards and merged passes, beside the vertex ones.
texel_direct_bytes=$(kind_bytes 'p.plan.pass0.texels.shard*') texel_bytes=$(kind_bytes 'p.plan.pass*.texels.*')
load=$(cut -d' ' -f1-3 /proc/loadavg)

echo "prt-bake $* ; $shards shards, $passes passes planned; $(nproc) cores; load $load"
echo
echo "| pass | shards, summed (s) | slowest shard (s) | merge (s) | shards, CPU (s) | merge, CPU (s) |"
echo "|---|---|---|---|---|---|"
printf '%s' "$rows"
printf '\none machine: %.2f s (CPU %.2f s); sharded, every step here in turn: %.2f s (%.2fx; CPU %.2f s, %+.1f%%); plan %.2f s, asset merge %.2f s\n' \
  "$one" "$one_cpu" "$total" "$(calc "$total / $one")" "$total_cpu" "$(calc "100 * ($total_cpu / $one_cpu - 1)")" "$plan_s" "$final"
printf 'critical path with %d machines (no queueing): %.2f s, a speed-up of %.2fx; work files %.1f MB; assets identical\n' \
  "$shards" "$critical" "$(calc "$one / $critical")" "$(calc "$bytes / 1000000")"
printf 'work files: direct shards %.1f MB, bounce shards %.1f MB, merged passes %.1f MB\n' \
  "$(calc "$direct_bytes / 1000000")" "$(calc "$bounce_bytes / 1000000")" "$(calc "$merged_bytes / 1000000")"
if ((texel_bytes > 0)); then
  printf 'texel files: %.1f MB (texel direct shards %.1f MB)\n' "$(calc "$texel_bytes / 1000000")" "$(calc "$texel_direct_bytes / 1000000")"
fi
if [[ -n $json ]]; then
  printf '{"args": "%s", "shards": %d, "passes": %d, "cores": %d, "load": "%s", "one_machine_s": %.3f, "one_machine_cpu_s": %.3f, "plan_s": %.3f, "plan_cpu_s": %.3f, "asset_merge_s": %.3f, "asset_merge_cpu_s": %.3f, "sharded_total_s": %.3f, "sharded_total_cpu_s": %.3f, "critical_path_s": %.3f, "work_bytes": %d, "direct_shard_bytes": %d, "bounce_shard_bytes": %d, "merged_pass_bytes": %d, "texel_bytes": %d, "texel_direct_shard_bytes": %d, "identical": true, "pass_rows": [%s]}\n' \
    "$*" "$shards" "$passes" "$(nproc)" "$load" "$one" "$one_cpu" "$plan_s" "$plan_cpu" "$final" "$final_cpu" "$total" "$total_cpu" \
    "$critical" "$bytes" "$direct_bytes" "$bounce_bytes" "$merged_bytes" "$texel_bytes" "$texel_direct_bytes" "$json_passes" > "$json"
fi
