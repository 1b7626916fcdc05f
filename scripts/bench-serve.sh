#!/usr/bin/env bash
# Benchmarks prt-serve against nginx (Debian) with wrk on loopback, and soaks prt-serve to
# watch its resident memory. Refreshes docs/bench/serve.json and docs/bench/serve.md.
#
# Usage: scripts/bench-serve.sh [--seconds N] [--soak N]
#   --seconds N  length of each wrk run (default 20)
#   --soak N     length of the memory soak (default 60)
# Runs: a ~1 MB asset and the catalogue JSON, each from prt-serve and from nginx serving the
# same files from the same directory, 64 connections. Installs wrk and nginx if missing
# (bench only; scripts/install-deps.sh does not). Run it on an otherwise idle machine.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

seconds=20
soak=60
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds="$2"; shift 2 ;;
    --soak) soak="$2"; shift 2 ;;
    *) echo "bench-serve.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
connections=64
wrk_threads=2
rss_interval=2

# Bench-only tools.
missing=()
command -v wrk >/dev/null || missing+=(wrk)
command -v nginx >/dev/null || [[ -x /usr/sbin/nginx ]] || missing+=(nginx)
if ((${#missing[@]})); then
  sudo=()
  [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  echo "bench-serve.sh: installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get update -q
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
nginx_bin="$(command -v nginx || echo /usr/sbin/nginx)"

build="$root/build/native"
cmake --preset native >/dev/null
cmake --build --preset native --target prt-serve prt_serve_make_asset

work="$root/build/bench-serve"
rm -rf "$work"
mkdir -p "$work/root" "$work/raw"
umask 022
# ~1 MB: 3500 vertices at SH order 4, an unshadowed and an interreflected pass.
asset_bytes=$("$build/tests/prt_serve_make_asset" "$work/root/bench.prt" 3500 4)

pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT

free_port() { node -e 'const s=require("net").createServer().listen(0,"127.0.0.1",()=>{console.log(s.address().port);s.close()})'; }

# prt-serve, as deployed: no access log, one I/O thread per core.
"$build/server/prt-serve" --root "$work/root" --port 0 --quiet >"$work/prt.out" 2>"$work/prt.err" &
prt_pid=$!
pids+=("$prt_pid")
for _ in $(seq 100); do grep -q listening "$work/prt.out" 2>/dev/null && break; sleep 0.1; done
prt_base=$(grep -o 'http://[^ ]*' "$work/prt.out" | sed 's|/$||')
[[ -n "$prt_base" ]] || { echo "bench-serve.sh: prt-serve did not start: $(cat "$work/prt.err")" >&2; exit 1; }
curl -sf "$prt_base/api/scenes" >"$work/root/scenes.json"
asset_url=$(node -e 'const c=JSON.parse(require("fs").readFileSync(process.argv[1]));console.log(c.scenes.find(s=>s.usable).url)' "$work/root/scenes.json")
catalogue_bytes=$(stat -c %s "$work/root/scenes.json")

# nginx on the same directory: /bench.prt and /scenes.json (a copy of prt-serve's document).
nginx_port=$(free_port)
workers=$(nproc)
sed -e "s|@WORK@|$work|g" -e "s|@ROOT@|$work/root|g" -e "s|@PORT@|$nginx_port|g" -e "s|@WORKERS@|$workers|g" \
  bench/serve/nginx.conf.in >"$work/nginx.conf"
"$nginx_bin" -c "$work/nginx.conf" -e "$work/nginx-error.log" &
nginx_pid=$!
pids+=("$nginx_pid")
nginx_base="http://127.0.0.1:$nginx_port"
for _ in $(seq 100); do curl -sf -o /dev/null "$nginx_base/scenes.json" && break; sleep 0.1; done
cmp <(curl -sf "$prt_base$asset_url") <(curl -sf "$nginx_base/bench.prt") || { echo "bench-serve.sh: servers disagree on the asset" >&2; exit 1; }
cmp <(curl -sf "$prt_base/api/scenes") <(curl -sf "$nginx_base/scenes.json") || { echo "bench-serve.sh: servers disagree on the catalogue" >&2; exit 1; }

# CPU accounting, to tell whether something else competed during a run: clock ticks the
# machine had (all CPUs), and ticks used by every user process but the server(s) and this
# script, children included (so a build's compilers count through make or ninja). wrk runs
# inside the window and is reaped by this script, so it is not counted.
machine_ticks() { awk '/^cpu / {print $2+$3+$4+$5+$6+$7+$8+$9}' /proc/stat; }
other_ticks() {  # PIDS TO LEAVE OUT...
  local skip=" $* $$ " f sum=0 pid
  for f in /proc/[0-9]*/stat; do
    pid=${f#/proc/}
    pid=${pid%/stat}
    [[ $skip == *" $pid "* ]] && continue
    # After the ") ", field 2 is the parent: kernel threads (children of kthreadd, pid 2)
    # are left out, since on loopback they mostly carry the benchmark's own network work.
    sum=$((sum + $(sed 's/.*) //' "$f" 2>/dev/null | awk '{print ($2 == 2 ? 0 : $12 + $13 + $14 + $15)}' || echo 0)))
  done 2>/dev/null
  echo "$sum"
}
server_pids() {  # prt | nginx: the server's processes
  if [[ $1 == prt ]]; then echo "$prt_pid"; else echo "$nginx_pid" $(pgrep -P "$nginx_pid"); fi
}
percent() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f\n", (b > 0 ? a / b * 100 : 0) }'; }

run_wrk() {  # NAME URL SECONDS SERVER(prt|nginx)
  echo "bench-serve.sh: wrk $2 for $3 s"
  local pids ticks0 other0 ticks1 other1
  pids=$(server_pids "$4")
  ticks0=$(machine_ticks)
  other0=$(other_ticks $pids)
  wrk -t"$wrk_threads" -c"$connections" -d"${3}s" --latency -s bench/serve/wrk_report.lua "$2" >"$work/raw/$1.txt"
  other1=$(other_ticks $pids)
  ticks1=$(machine_ticks)
  percent $((other1 - other0)) $((ticks1 - ticks0)) >"$work/raw/$1.other"
  grep -E 'Requests/sec|Latency  |Non-2xx|Socket errors' "$work/raw/$1.txt" || true
  echo "  other processes: $(cat "$work/raw/$1.other")% of the machine's CPU"
}

# A short warm-up of each, then the measured runs back to back.
wrk -t"$wrk_threads" -c"$connections" -d2s "$prt_base$asset_url" >/dev/null
wrk -t"$wrk_threads" -c"$connections" -d2s "$nginx_base/bench.prt" >/dev/null
run_wrk prt-asset "$prt_base$asset_url" "$seconds" prt
run_wrk nginx-asset "$nginx_base/bench.prt" "$seconds" nginx
run_wrk prt-catalogue "$prt_base/api/scenes" "$seconds" prt
run_wrk nginx-catalogue "$nginx_base/scenes.json" "$seconds" nginx

# Soak: prt-serve's resident memory while it serves the asset for $soak seconds.
: >"$work/raw/rss.txt"
ticks0=$(machine_ticks)
other0=$(other_ticks "$prt_pid")
wrk -t"$wrk_threads" -c"$connections" -d"${soak}s" --latency -s bench/serve/wrk_report.lua "$prt_base$asset_url" \
  >"$work/raw/soak.txt" &
wrk_pid=$!
for ((t = 0; t <= soak; t += rss_interval)); do
  echo "$t $(awk '/^VmRSS/ {print $2}' /proc/$prt_pid/status)" >>"$work/raw/rss.txt"
  sleep "$rss_interval"
done
# wrk is still running at the last sample: leave it out explicitly.
other1=$(other_ticks "$prt_pid" "$wrk_pid")
wait "$wrk_pid"
ticks1=$(machine_ticks)
percent $((other1 - other0)) $((ticks1 - ticks0)) >"$work/raw/soak.other"

cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
cat >"$work/raw/meta.json" <<JSON
{
  "date": "$(date -u +%Y-%m-%dT%H:%M:%SZ)",
  "machine": {"cpu": "$cpu", "cores": $(nproc), "kernel": "$(uname -sr)", "memory_gib": $(awk '/MemTotal/ {printf "%.1f", $2/1048576}' /proc/meminfo)},
  "tools": {"wrk": "$(wrk -v 2>&1 | head -1 | cut -d' ' -f1-2)", "nginx": "$("$nginx_bin" -v 2>&1 | sed 's/^nginx version: //')"},
  "settings": {"connections": $connections, "wrk_threads": $wrk_threads, "seconds": $seconds,
               "prt_serve": "--threads $(nproc) (default) --quiet", "nginx": "worker_processes $workers, sendfile, access_log off",
               "rss_interval_s": $rss_interval},
  "asset_bytes": $asset_bytes,
  "catalogue_bytes": $catalogue_bytes,
  "soak_seconds": $soak
}
JSON
mkdir -p docs/bench
node bench/serve/report.mjs "$work/raw" docs/bench/serve.json docs/bench/serve.md
echo "bench-serve.sh: wrote docs/bench/serve.json and docs/bench/serve.md"
