#!/usr/bin/env bash
# Wall time of `hyst diagnose --model bw` on a 2,000-sample record with the
# four default candidate effects (issue 4: at most 10 s on this 2-core
# machine): the first 2,000 samples of Lehman and Moehle 415 (PEER SPD 369)
# and the 1,603 of the hidden-pinching record s1. Best of RUNS (default 3),
# with the load average before each run.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p hysteresis-host
data=../shared/data
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
head -n 2001 "$data/peer-spd-columns/fd/spd_369.csv" > "$tmp/spd_369_2000.csv"
for rec in "$tmp/spd_369_2000.csv" "$data/synthetic/s1_hidden_pinching.csv"; do
  samples=$(grep -cv '^#' "$rec")
  best=""
  for _ in $(seq "${RUNS:-3}"); do
    load=$(cut -d' ' -f1 /proc/loadavg)
    start=$(date +%s.%N)
    target/release/hyst diagnose "$rec" --model bw --json > "$tmp/out.json"
    t=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    echo "  $(basename "$rec") ($((samples - 1)) samples): ${t} s (load $load)"
    if [ -z "$best" ] || awk -v t="$t" -v b="$best" 'BEGIN { exit !(t < b) }'; then best=$t; fi
  done
  echo "$(basename "$rec"): best ${best} s"
done
