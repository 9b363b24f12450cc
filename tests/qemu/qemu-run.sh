#!/usr/bin/env bash
# Cargo runner for the on-target tests: boots the ELF in QEMU and decodes its
# defmt output. The firmware's exit code (semihosting SYS_EXIT_EXTENDED: 0
# pass, 101 panic, 102 HardFault) passes through the pipe; a hung firmware is
# stopped after QEMU_TIMEOUT seconds (exit 124).
set -euo pipefail
elf="$1"
shift
case "$elf" in
  */thumbv7m-none-eabi/*) machine=mps2-an385 ;; # Cortex-M3, no FPU
  *) machine=mps2-an386 ;;                      # Cortex-M4F
esac
timeout "${QEMU_TIMEOUT:-120}" qemu-system-arm -machine "$machine" -display none \
  -semihosting-config enable=on,target=native -kernel "$elf" </dev/null |
  defmt-print -e "$elf"
