#!/usr/bin/env bash
# Flat instruction profile of a firmware of this package under QEMU: where the
# executed instructions go, by source line and by function (inlined frames
# resolved from the release build's debug info).
#   profile.sh [BIN [TARGET]]     default: f32_only on thumbv7em-none-eabihf
# Needs the plugin built from insn_profile.c (see its header) in INSN_PROFILE.
set -euo pipefail
cd "$(dirname "$0")/.."
plugin="${INSN_PROFILE:?set INSN_PROFILE to libinsn_profile.so}"
bin="${1:-f32_only}"
target="${2:-thumbv7em-none-eabihf}"
case "$target" in
  thumbv7m-none-eabi) machine=mps2-an385 ;;
  *) machine=mps2-an386 ;;
esac
elf=$(cargo build --release --bin "$bin" --target "$target" --message-format=json-render-diagnostics |
  sed -n 's/.*"executable":"\([^"]*\)".*/\1/p')
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
qemu-system-arm -machine "$machine" -display none -semihosting-config enable=on,target=native \
  -plugin "$plugin,out=$work/counts" -d plugin -kernel "$elf" </dev/null >/dev/null 2>&1 || true
grep -v '^outside' "$work/counts" | awk '{ print "0x" $1 }' |
  llvm-addr2line -f -i -C --output-style=JSON -e "$elf" >"$work/frames"
python3 - "$work/counts" "$work/frames" <<'PY'
import collections, json, re, sys
counts = [l.split() for l in open(sys.argv[1]) if not l.startswith("outside")]
# One JSON object per address: its frames, innermost inlined frame first.
blocks = [json.loads(l)["Symbol"] for l in open(sys.argv[2])]
assert len(blocks) == len(counts), (len(blocks), len(counts))
total = sum(int(c) for _, c in counts)
by_line, by_fn, by_any, by_top, calls = (collections.Counter() for _ in range(5))


def short(f):
    f = re.sub(r"::h[0-9a-f]{16}$", "", f)
    for code, ch in [("$LT$", "<"), ("$GT$", ">"), ("$u20$", " "), ("$C$", ","), ("$u7b$", "{"), ("$u7d$", "}"), ("..", "::")]:
        f = f.replace(code, ch)
    while re.search(r"<[^<>]*>", f):
        f = re.sub(r"<[^<>]*>", "", f)
    return "::".join(f.split("::")[-2:])


for (addr, c), frames in zip(counts, blocks):
    c = int(c)
    inner = frames[0]
    loc = re.sub(r".*/(src/|library/)", r"\1", inner["FileName"]) + ":" + str(inner["Line"])
    by_line[loc] += c
    by_fn[short(inner["FunctionName"])] += c
    outer = frames[-1]
    by_top[short(outer["FunctionName"])] += c
    if int(addr, 16) == int(outer["StartAddress"], 16):
        calls[short(outer["FunctionName"])] += c
    for f in {short(fr["FunctionName"]) for fr in frames}:
        by_any[f] += c
print(f"total instructions: {total}")
print("\noutermost (not inlined) function: share, instructions, calls, per call")
for k, c in by_top.most_common(15):
    n = calls[k]
    print(f"  {100 * c / total:5.1f}%  {c:>10}  {n:>8}  {c / n if n else float('nan'):8.1f}  {k}")
for title, table in [("innermost function", by_fn), ("function incl. inlined callees", by_any), ("source line", by_line)]:
    print(f"\n{title}:")
    for k, c in table.most_common(40):
        print(f"  {100 * c / total:5.1f}%  {c:>10}  {k}")
PY
