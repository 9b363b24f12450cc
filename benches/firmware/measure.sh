#!/usr/bin/env bash
# Instructions per call of each case in src/main.rs, counted exactly under QEMU by the
# insn_marker TCG plugin (shared/tools/qemu-insn) between bench_start() and bench_stop().
#
# usage: benches/firmware/measure.sh [m4f|m3|all]     (default: all)
# Needs qemu-system-arm, gcc (to build the plugin once), rust-nm/rust-objdump
# (cargo-binutils + llvm-tools) and the thumbv7em-none-eabihf / thumbv7m-none-eabi targets.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cd "$here"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$here/target}"
plugin="${INSN_PLUGIN:-$CARGO_TARGET_DIR/libinsn_marker.so}"
if [ ! -f "$plugin" ]; then
    src="$here/../../../shared/tools/qemu-insn/insn_marker.c"
    mkdir -p "$(dirname "$plugin")"
    gcc -O2 -shared -fPIC -fvisibility=hidden -o "$plugin" "$src"
fi

run() { # target machine label
    local target="$1" machine="$2" label="$3"
    cargo build --release --quiet --target "$target"
    local elf="$CARGO_TARGET_DIR/$target/release/hysteresis-firmware-bench"
    local start stop
    start=$(rust-nm "$elf" | awk '$3=="bench_start"{print "0x"$1}')
    stop=$(rust-nm "$elf" | awk '$3=="bench_stop"{print "0x"$1}')
    [ "$start" != "$stop" ] || { echo "bench_start and bench_stop share an address (ICF)"; exit 1; }
    local out="$CARGO_TARGET_DIR/$label"
    timeout 300 qemu-system-arm -machine "$machine" -display none \
        -semihosting-config enable=on,target=native \
        -plugin "$plugin,start=$start,stop=$stop" -d plugin -kernel "$elf" \
        2>"$out.plugin.log" >"$out.cases.log" </dev/null
    echo "== $label ($target on $machine): instructions per call"
    paste -d' ' <(grep '^case' "$out.cases.log" | awk '{print $2}') \
                <(grep '^bench' "$out.plugin.log" | awk '{print $3}') |
    awk '{ if ($1=="baseline") { base=$2; printf "  %-16s %8.1f (loop skeleton per iteration)\n", $1, $2/1024 }
           else printf "  %-16s %8.1f\n", $1, ($2-base)/1024 }'
    if [ "$label" = m4f ]; then
        # No f64 may reach the f32 path: no double-precision register and no soft-float
        # double call in any f32 function of the core.
        local syms
        syms=$(rust-nm "$elf" | awk '{print $3}' | grep -E 'fastmath3f32|fast_powf_call|fast_expf_call' || true)
        local bad=0
        for s in $syms; do
            if rust-objdump -d --no-show-raw-insn --disassemble-symbols="$s" "$elf" |
                grep -Eq '__aeabi_d|__adddf3|__muldf3|\bd[0-9]+\b|\.f64'; then
                echo "  f64 operation in $s"; bad=1
            fi
        done
        [ "$bad" = 0 ] && echo "  f32 path: no f64 operation in $(echo "$syms" | wc -w) functions" || exit 1
    fi
}

case "${1:-all}" in
    m4f) run thumbv7em-none-eabihf mps2-an386 m4f ;;
    m3) run thumbv7m-none-eabi mps2-an385 m3 ;;
    all) run thumbv7em-none-eabihf mps2-an386 m4f; run thumbv7m-none-eabi mps2-an385 m3 ;;
    *) echo "usage: $0 [m4f|m3|all]"; exit 2 ;;
esac
