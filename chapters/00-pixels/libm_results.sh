#!/bin/sh
# The committed, dated comparison of the C library's mathematical functions across machines
# (chapters/00-pixels/libm_results.md), which chapter 0's section "What exact results rely
# on" quotes: libm_agreement.cpp, built for this x86-64 machine and for ARM64 (run under
# qemu-user), and run again here with glibc's FMA variants switched off.
# Needs the arm64 workflow's packages (README.md) and a CPU with FMA.
# Usage (from the repository root): chapters/00-pixels/libm_results.sh ["note"]
set -eu
note=${1:-}
out=chapters/00-pixels/libm_results.md
source=chapters/00-pixels/libm_agreement.cpp
grep -qw fma /proc/cpuinfo || { echo "libm_results.sh: this CPU has no FMA" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
c++ -std=c++20 -O2 -ffp-contract=off -o "$work/x86-64" "$source"
aarch64-linux-gnu-g++ -std=c++20 -O2 -ffp-contract=off -o "$work/arm64" "$source"
"$work/x86-64" write "$work/x86-64.bin"
GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA "$work/x86-64" write "$work/x86-64-nofma.bin"
qemu-aarch64 -L /usr/aarch64-linux-gnu "$work/arm64" write "$work/arm64.bin"
glibc=$(ldd --version | head -n 1 | sed 's/.* //')
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)
header() {
    echo
    echo ": Scene \"$1\": $2"
    echo
    echo "| function | where the library calls it, on which arguments | differ | % | most ulp |"
    echo "|:--|:--|--:|--:|--:|"
}
{
    echo "# Chapter 0: the C library's functions on two machines"
    echo
    echo "Measured $(date -u +%Y-%m-%d) on $(uname -m) ($cpu) with glibc $glibc," \
         "against the same glibc's arm64 build run under $(qemu-aarch64 --version | head -n 1):" \
         "one million arguments per function ($source says which)."
    echo "Regenerate with"
    echo
    echo '```{.sh}'
    echo "chapters/00-pixels/libm_results.sh"
    echo '```'
    echo
    [ -z "$note" ] || { echo "$note"; echo; }
    header arm64 "results of glibc on ARM64 that differ from those on x86-64 (with FMA)."
    "$work/x86-64" compare "$work/x86-64.bin" "$work/arm64.bin"
    header nofma "results of glibc on x86-64 without its FMA variants (GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA, as on a CPU without FMA) that differ from those with them."
    "$work/x86-64" compare "$work/x86-64.bin" "$work/x86-64-nofma.bin"
} >"$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
