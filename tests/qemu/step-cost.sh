#!/usr/bin/env bash
# Exact instruction counts per step of src/bin/step_cost.rs on both targets,
# with the qemu-insn plugin (../../../shared/tools/qemu-insn; build it with
#   gcc -O2 -shared -fPIC -fvisibility=hidden -o libinsn_marker.so insn_marker.c
# and point INSN_PLUGIN at it).
set -euo pipefail
cd "$(dirname "$0")"
plugin="${INSN_PLUGIN:?set INSN_PLUGIN to libinsn_marker.so}"
log=$(mktemp -d)
trap 'rm -rf "$log"' EXIT
for pair in thumbv7em-none-eabihf:mps2-an386 thumbv7m-none-eabi:mps2-an385; do
  target=${pair%%:*}
  machine=${pair##*:}
  elf=$(cargo build --release --bin step_cost --target "$target" --message-format=json-render-diagnostics |
    sed -n 's/.*"executable":"\([^"]*\)".*/\1/p')
  start=$(rust-nm "$elf" | awk '$3 == "bench_start" { print "0x" $1 }')
  stop=$(rust-nm "$elf" | awk '$3 == "bench_stop" { print "0x" $1 }')
  qemu-system-arm -machine "$machine" -display none -semihosting-config enable=on,target=native \
    -plugin "$plugin,start=$start,stop=$stop" -d plugin -kernel "$elf" </dev/null \
    2>"$log/plugin" | defmt-print -e "$elf" >"$log/cases"
  echo "$target ($machine): instructions per step, reference history"
  paste -d' ' <(grep '^case' "$log/cases" | awk '{ print $2 }') \
    <(grep '^bench' "$log/plugin" | awk '{ print $3 }') |
    awk '$1 ~ /step$/ { n[$1]++; sum[$1] += $2; if ($2 > max[$1]) max[$1] = $2; next }
         $1 ~ /^history\// { split($1, h, "/"); loop[h[2]] = $2 / 3600 }
         $1 ~ /^phm\// { split($1, h, "/"); printf "  %-28s %8.0f  (%.0f net of the history loop)\n", $1, $2 / 3600, $2 / 3600 - loop[h[2]]; next }
         { printf "  %-28s %8.0f\n", $1, $2 / 3600 }
         END { for (k in n) printf "  %-28s mean %.0f, worst %d (%d steps, markers included)\n", k, sum[k] / n[k], max[k], n[k] }'
done
