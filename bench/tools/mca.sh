#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bench/tools/mca.sh - the cycles of one kernel's hot path on other cores, by llvm-mca's
# models: for a microarchitecture that is not at hand (AMD Zen on an Intel machine, or
# the reverse).
#
#   bench/tools/mca.sh [--isa=avx2] [--driver=stream] [--flags=normal]
#                      [--scenario=incoherent] [--stores=lanes|masked]
#                      [--cpus=znver3,znver4,sapphirerapids] [--keep=FILE]
#
# Runs one configuration of the harness (cylicount) under callgrind with the count of
# every instruction, takes the kernel function of libcylray that ran the most
# instructions (with --driver=textbook, the auto-vectorized peer's loop in cylicount),
# and keeps the instructions of it that ran as many times as most of its instructions
# did: the straight path that every call or pair runs (no branch, no store loop, no
# rare path). That trace, in address order, goes through llvm-mca once
# (the latency of one pass) and 100 times back to back (the steady state), per model.
# A pass is one call of a packet function, or one pair of a stream's vectors.
#
# --stores: the store policy (CYLRAY_STORES) the trace is taken with; `lanes` is what
# AMD Zen 1-3 run (its loop over the hit lanes is left out of the trace, as every
# branch is), `masked` what Intel runs. --keep writes the trace to FILE.
#
# AVX-512 cannot be traced: valgrind does not run it (bench/README.md, icount.sh).
# Needs valgrind and an llvm-mca of LLVM 16 or later: LLVM 14's znver3 model takes a
# 256-bit FMA as one a cycle, where Zen 2 and 3 run two (docs/performance.md).
# Environment: CYLBENCH_BUILD as for icount.sh (default build-bench/, a release build).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
root=$(dirname "$here")
build=${CYLBENCH_BUILD:-$root/build-bench}
isa=avx2 driver=stream flags=normal scenario=incoherent stores=lanes keep=""
cpus="znver3 znver4 sapphirerapids"
for a in "$@"; do
    case $a in
    --isa=*) isa=${a#*=} ;;
    --driver=*) driver=${a#*=} ;;
    --flags=*) flags=${a#*=} ;;
    --scenario=*) scenario=${a#*=} ;;
    --stores=*) stores=${a#*=} ;;
    --cpus=*) cpus=${a#*=}; cpus=${cpus//,/ } ;;
    --keep=*) keep=${a#*=} ;;
    *) sed -n '2,27s/^# \{0,1\}//p' "$0" >&2; exit 1 ;;
    esac
done

mca=""
for v in 22 21 20 19 18 17 16; do
    command -v "llvm-mca-$v" >/dev/null 2>&1 && { mca=llvm-mca-$v; break; }
done
if [ -z "$mca" ] && command -v llvm-mca >/dev/null 2>&1; then
    major=$(llvm-mca --version | sed -n 's/.*LLVM version \([0-9]*\).*/\1/p')
    [ "${major:-0}" -ge 16 ] && mca=llvm-mca
fi
for tool in valgrind python3 objdump meson ninja; do
    command -v "$tool" >/dev/null 2>&1 || {
        echo "mca.sh: $tool is not installed; install it first (nothing is installed here)" >&2
        exit 1
    }
done
[ -n "$mca" ] || {
    echo "mca.sh: needs llvm-mca of LLVM 16 or later (e.g. apt install llvm-19)" >&2
    exit 1
}

if [ -f "$build/build.ninja" ]; then
    meson configure "$build" -Dbuildtype=release -Dbench=true >/dev/null
else
    meson setup "$build" "$root" -Dbuildtype=release -Dtests=false -Dbench=true >/dev/null
fi
ninja -C "$build" bench/tools/cylicount >/dev/null
lib=$(readlink -f "$build/src/libcylray.so")
prefix=""
if [ "$driver" = textbook ]; then
    lib=$(readlink -f "$build/bench/tools/cylicount")
    prefix=tb_
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
CYLRAY_STORES=$stores valgrind --tool=callgrind --dump-instr=yes --compress-pos=no \
    --compress-strings=no --callgrind-out-file="$tmp/cg" "$build/bench/tools/cylicount" \
    --isa="$isa" --driver="$driver" --flags="$flags" --scenario="$scenario" --passes=16 \
    >"$tmp/log" 2>&1 || { cat "$tmp/log" >&2; exit 1; }

python3 - "$tmp/cg" "$lib" "$prefix" >"$tmp/trace.s" 2>"$tmp/what" <<'EOF'
import collections, re, subprocess, sys
cg, lib, prefix = sys.argv[1:4]
cost = collections.defaultdict(collections.Counter)  # function -> address -> count
obj = fn = None
call = False
for line in open(cg):
    if line.startswith("ob="):
        obj = line[3:].strip()
    elif line.startswith("fn="):
        fn, call = line[3:].strip(), False
        fn = fn if fn.startswith(prefix) else None
    elif line.startswith("calls="):
        call = True  # the next cost line is the call's inclusive cost
    elif re.match(r"^0x[0-9a-f]+ ", line) and fn and obj and obj.endswith(lib.split("/")[-1]):
        if call:
            call = False
            continue
        a, _, n = line.split()[:3]
        cost[fn][int(a, 16)] += int(n)
fn = max(cost, key=lambda f: sum(cost[f].values()))
counts = collections.Counter(cost[fn].values())
passes = max(counts, key=lambda c: (counts[c], c))
syms = subprocess.run(["nm", lib], capture_output=True, text=True).stdout.split("\n")
entry = next(int(s.split()[0], 16) for s in syms if s.split()[-1:] == [fn])
base = min(cost[fn]) - entry  # the function's entry ran: callgrind's load offset
dis = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "--start-address=%d" % entry,
                      "--stop-address=%d" % (entry + 65536), lib],
                     capture_output=True, text=True).stdout
text = {}
for l in dis.splitlines():
    m = re.match(r"^\s+([0-9a-f]+):\s+(.*)$", l)
    if m:
        text[int(m.group(1), 16)] = m.group(2).split("#")[0].split("<")[0].strip()
kept = [text[a - base] for a in sorted(cost[fn])
        if cost[fn][a] == passes and a - base in text
        and not text[a - base].startswith(("j", "call", "ret"))]
print("\n".join(kept))
sys.stderr.write("%s %d %d\n" % (fn, passes, len(kept)))
EOF
read -r fn passes n <"$tmp/what"
[ -n "$keep" ] && cp "$tmp/trace.s" "$keep"
echo "$scenario $isa $driver $flags, stores $stores:" \
    "$fn, $n instructions a pass (ran $passes times)"
echo "$mca:"
for cpu in $cpus; do
    one=$("$mca" -mcpu="$cpu" -iterations=1 "$tmp/trace.s" 2>/dev/null |
        awk '/^Total Cycles/ { print $3 }')
    many=$("$mca" -mcpu="$cpu" -iterations=100 "$tmp/trace.s" 2>/dev/null |
        awk '/^Total Cycles/ { c = $3 } /^Total uOps/ { u = $3 }
             END { printf "%.1f %.0f", c / 100, u / 100 }')
    read -r steady uops <<<"$many"
    printf '  %-16s one pass %5s cycles   100 back to back %7s cycles a pass   %5s uops a pass\n' \
        "$cpu" "$one" "$steady" "$uops"
done
