#!/usr/bin/env bash
# Exact instruction counts of src/bin/tick_cost.rs (table load, element
# build, control tick for 1, 8 and 64 elements) on the Cortex-M4F, with the
# qemu-insn plugin (../../../shared/tools/qemu-insn; build it with
#   gcc -O2 -shared -fPIC -fvisibility=hidden -o libinsn_marker.so insn_marker.c
# and point INSN_PLUGIN at it). Also prints rust-size of both firmware bins.
set -euo pipefail
cd "$(dirname "$0")"
plugin="${INSN_PLUGIN:?set INSN_PLUGIN to libinsn_marker.so}"
log=$(mktemp -d)
trap 'rm -rf "$log"' EXIT
elf() {
  cargo build --release --bin "$1" --message-format=json-render-diagnostics |
    sed -n 's/.*"executable":"\([^"]*\)".*/\1/p'
}
bench=$(elf tick_cost)
start=$(rust-nm "$bench" | awk '$3 == "bench_start" { print "0x" $1 }')
stop=$(rust-nm "$bench" | awk '$3 == "bench_stop" { print "0x" $1 }')
qemu-system-arm -machine mps2-an386 -display none -semihosting-config enable=on,target=native \
  -plugin "$plugin,start=$start,stop=$stop" -d plugin -kernel "$bench" </dev/null \
  2>"$log/plugin" | defmt-print -e "$bench" >"$log/cases"
grep '^bench' "$log/plugin" | awk '{ print $3 }' >"$log/counts"
echo "thumbv7em-none-eabihf (mps2-an386), instructions (markers subtracted):"
printf '  %-12s %10s %10s %10s\n' case mean max min
grep '^case' "$log/cases" | awk -v counts="$log/counts" '
  { name = $2; n = $3; sum = 0; max = 0; min = -1
    for (i = 0; i < n; i++) { getline c < counts; sum += c; if (c > max) max = c; if (min < 0 || c < min) min = c }
    if (name == "baseline") { base = sum / n; next }
    printf "  %-12s %10.0f %10.0f %10.0f\n", name, sum / n - base, max - base, min - base }'
echo "sizes (rust-size, bytes):"
for bin in control tick_cost; do
  rust-size "$(elf "$bin")" | tail -n1 |
    awk -v b="$bin" '{ printf "  %-10s text %s, data %s, bss %s\n", b, $1, $2, $3 }'
done
