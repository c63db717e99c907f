#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bench/tools/stages.sh - instructions a ray by kernel stage: where a kernel's work goes,
# on machines whose performance counters are out of reach (virtual machines).
#
#   bench/tools/stages.sh [--isa=avx2] [--driver=stream] [--flags=normal]
#                         [--scenario=incoherent] [--passes=64] [--lines=N]
#
# Runs one configuration of the harness (cylicount) under callgrind with the count of
# every instruction, and charges each instruction of libcylray to the kernel stage it
# was inlined from (src/kernel/*.h: reject, shift, side_coefs, roots, ends, decide,
# normals, store, ...), read from the inlining records of a build with debug
# information (addr2line -i). An instruction inlined through several stages goes to the
# innermost one; one outside every stage goes to its function (the driver). --lines=N
# also lists the N source lines of src/kernel/ that ran the most instructions.
#
# The counts are valgrind's: instructions, not cycles (a division counts as one). They
# show which stage to look at, not what it costs in time: for that, cylbench times the
# whole and mca.sh reads the hot path through llvm-mca's models.
#
# AVX-512 cannot be counted: valgrind does not run it (bench/README.md, icount.sh).
# Environment: CYLSTAGES_BUILD (build directory, default build-stages/ at the top of the
# repository: a release build with debug information, which changes no instruction).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
root=$(dirname "$here")
build=${CYLSTAGES_BUILD:-$root/build-stages}
isa=avx2 driver=stream flags=normal scenario=incoherent passes=64 lines=0
for a in "$@"; do
    case $a in
    --isa=*) isa=${a#*=} ;;
    --driver=*) driver=${a#*=} ;;
    --flags=*) flags=${a#*=} ;;
    --scenario=*) scenario=${a#*=} ;;
    --passes=*) passes=${a#*=} ;;
    --lines=*) lines=${a#*=} ;;
    *) sed -n '2,23s/^# \{0,1\}//p' "$0" >&2; exit 1 ;;
    esac
done
if [ "$driver" = textbook ]; then
    echo "stages.sh: the textbook loop has no stages (icount.sh counts it)" >&2
    exit 1
fi
for tool in valgrind python3 addr2line meson ninja; do
    command -v "$tool" >/dev/null 2>&1 || {
        echo "stages.sh: $tool is not installed; install it first (nothing is installed here)" >&2
        exit 1
    }
done

if [ -f "$build/build.ninja" ]; then
    meson configure "$build" -Dbuildtype=release -Ddebug=true -Dbench=true >/dev/null
else
    meson setup "$build" "$root" -Dbuildtype=release -Ddebug=true -Dtests=false \
        -Dbench=true >/dev/null
fi
ninja -C "$build" bench/tools/cylicount >/dev/null
lib=$(readlink -f "$build/src/libcylray.so")

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
valgrind --tool=callgrind --dump-instr=yes --compress-pos=no --compress-strings=no \
    --callgrind-out-file="$tmp/cg" "$build/bench/tools/cylicount" --isa="$isa" \
    --driver="$driver" --flags="$flags" --scenario="$scenario" --passes="$passes" \
    >"$tmp/log" 2>&1 || { cat "$tmp/log" >&2; exit 1; }
rays=$(sed -n 's/.*passes, \([0-9]*\) rays.*/\1/p' "$tmp/log")
[ -n "$rays" ] || { echo "stages.sh: cannot read the rays in: $(cat "$tmp/log")" >&2; exit 1; }

echo "$scenario $isa $driver $flags ($rays rays): instructions a ray in libcylray"
python3 - "$tmp/cg" "$lib" "$rays" "$lines" <<'EOF'
import collections, re, subprocess, sys
cg, lib, rays, nlines = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
cost = collections.Counter()  # address in the library -> instructions
obj, call = None, False
for line in open(cg):
    if line.startswith("ob="):
        obj = line[3:].strip()
    elif line.startswith("fn="):
        call = False
    elif line.startswith("calls="):
        call = True  # the next cost line is the call's inclusive cost
    elif re.match(r"^0x[0-9a-f]+ ", line) and obj == lib:
        if call:
            call = False
            continue
        a, _, n = line.split()[:3]
        cost[int(a, 16)] += int(n)
if not cost:
    sys.exit("stages.sh: no instruction of %s ran" % lib)
# (callgrind gives a shared library's addresses as addr2line reads them: from its start)
addrs = sorted(cost)
frames = {}
out = subprocess.run(["addr2line", "-i", "-f", "-a", "-e", lib],
                     input="\n".join(hex(a) for a in addrs), capture_output=True,
                     text=True).stdout.split("\n")
cur = None
for l in out:
    if re.match(r"^0x[0-9a-f]+$", l):
        cur = int(l, 16)
        frames[cur] = []
    elif l and cur is not None:
        frames[cur].append(l)
isa_tail = re.compile(r"_(scalar|sse41|avx2|avx512|neon)_\d+$")
stage, where = collections.Counter(), collections.Counter()
for a, n in cost.items():
    fr = frames.get(a, [])
    pairs = [(fr[j], fr[j + 1]) for j in range(0, len(fr) - 1, 2)]
    # innermost first: the first frame whose body is in a kernel header names the stage
    kern = [(f, loc) for f, loc in pairs if "/src/kernel/" in loc]
    if kern:
        name = isa_tail.sub("", kern[0][0])
        where[kern[0][1].split("/src/")[1].split(" ")[0]] += n
    else:
        name = isa_tail.sub("", pairs[-1][0]) + " (driver)" if pairs else "?"
    stage[name] += n
total = sum(stage.values())
print("  %-28s %8.1f" % ("all", total / rays))
for name, n in stage.most_common():
    if n / rays >= 0.05:
        print("  %-28s %8.1f  %5.1f %%" % (name, n / rays, 100.0 * n / total))
if nlines:
    print("the source lines of src/kernel/ that ran the most (the stage's line itself):")
    for loc, n in where.most_common(nlines):
        print("  %-28s %8.1f  %5.1f %%" % (loc, n / rays, 100.0 * n / total))
EOF
