#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bench/tools/icount.sh - instructions per ray of every kernel driver, counted by valgrind, for
# machines whose performance counters are out of reach (virtual machines, containers).
#
#   bench/tools/icount.sh [--passes=N] [--check] [--isa=LIST] [--scenario=LIST]
#
# Each configuration (ISA x driver x flag set x scenario) runs twice under callgrind,
# with N and 2N passes (default 16) over the scenario's 512-ray batches, and reports
# (Ir(2N) - Ir(N)) / (rays of N passes): start-up, ray generation and packing cancel.
# N is best a multiple of 8, the batches in a scenario, so that every batch counts
# alike. --check also runs 4N passes and prints the per-ray figure of 2N -> 4N beside it
# (a drift would mean something in the pass is not the same from pass to pass).
#
# Environment: CYLBENCH_BUILD, CYLBENCH_OUT (as for run.sh: build-bench/ and bench/out),
# CYLICOUNT_CPU (a core to pin valgrind to with taskset, e.g. to stay off a core that
# is timing something). Writes icount.csv to the output directory.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
root=$(dirname "$here")
build=${CYLBENCH_BUILD:-$root/build-bench}
out=${CYLBENCH_OUT:-$here/out}
passes=16
check=0
isas="scalar sse41 avx2 avx512 neon"
scenarios="coherent incoherent"
drivers="4 8 16 stream textbook"
flagsets="t normal occluded refine fast"
for a in "$@"; do
    case $a in
    --passes=*) passes=${a#*=} ;;
    --check) check=1 ;;
    --isa=*) isas=${a#*=}; isas=${isas//,/ } ;;
    --scenario=*) scenarios=${a#*=}; scenarios=${scenarios//,/ } ;;
    *) sed -n '2,17s/^# \{0,1\}//p' "$0" >&2; exit 1 ;;
    esac
done

for tool in valgrind meson ninja; do
    command -v "$tool" >/dev/null 2>&1 || {
        echo "icount.sh: $tool is not installed; install it first (nothing is installed here)" >&2
        exit 1
    }
done

# The same release build as run.sh, in the same directory.
if [ -f "$build/build.ninja" ]; then
    meson configure "$build" -Dbuildtype=release -Dtests=false -Dbench=true >/dev/null
else
    meson setup "$build" "$root" -Dbuildtype=release -Dtests=false -Dbench=true >/dev/null
fi
ninja -C "$build" bench/tools/cylicount >/dev/null
exe=$build/bench/tools/cylicount

pin=()
[ -n "${CYLICOUNT_CPU:-}" ] && pin=(taskset -c "$CYLICOUNT_CPU")

# One run: "instructions rays" on stdout, or the exit status of cylicount (2: not
# available here, 3: not a combination the harness measures).
count() {
    local log st=0
    log=$("${pin[@]}" valgrind --tool=callgrind --callgrind-out-file=/dev/null \
        "$exe" "$@" 2>&1) || st=$?
    [ "$st" -eq 0 ] || return "$st"
    local ir rays
    ir=$(sed -n 's/.*Collected : *\([0-9]*\).*/\1/p' <<<"$log")
    rays=$(sed -n 's/.*passes, \([0-9]*\) rays.*/\1/p' <<<"$log")
    if [ -z "$ir" ] || [ -z "$rays" ]; then
        echo "icount.sh: cannot read the count in: $log" >&2
        exit 1
    fi
    echo "$ir $rays"
}

# Which paths run under valgrind here: one pass of each, once. AVX-512 is not even
# tried: valgrind has no AVX-512 (the CPU it reports to the program has none either).
vg=$(valgrind --version)
run_isas=""
notes=()
for isa in $isas; do
    if [ "$isa" = avx512 ]; then
        notes+=("avx512: skipped, $vg does not run AVX-512 code")
        continue
    fi
    st=0
    count --isa="$isa" --driver=stream --flags=t --scenario=coherent --passes=1 \
        >/dev/null 2>&1 || st=$?
    case $st in
    0) run_isas+=" $isa" ;;
    2) notes+=("$isa: skipped, not built here or not a path of this CPU") ;;
    *) echo "icount.sh: cylicount failed on $isa (status $st)" >&2; exit 1 ;;
    esac
done

mkdir -p "$out"
csv=$out/icount.csv
echo "scenario,isa,driver,flags,passes,ir_n,ir_2n,instr_per_ray,instr_per_ray_check" >"$csv"
start=$SECONDS
w=9
[ "$check" -eq 1 ] && w=13
for s in $scenarios; do
    printf '\n%s: instructions per ray (N=%s vs %s passes of 512 rays)\n' "$s" "$passes" \
        $((2 * passes))
    printf '%-8s %-9s' isa driver
    for f in $flagsets; do printf " %${w}s" "$f"; done
    echo
    for isa in $run_isas; do
        for d in $drivers; do
            line=$(printf '%-8s %-9s' "$isa" "$d")
            for f in $flagsets; do
                args=(--isa="$isa" --driver="$d" --flags="$f" --scenario="$s")
                st=0
                a=$(count "${args[@]}" --passes="$passes") || st=$?
                if [ "$st" -ne 0 ]; then
                    # 3: a combination the harness does not measure either; 2: a build
                    # of the textbook peer that is missing here
                    [ "$st" -eq 2 ] || [ "$st" -eq 3 ] ||
                        { echo "icount.sh: cylicount failed: ${args[*]}" >&2; exit 1; }
                    line+=$(printf " %${w}s" -)
                    continue
                fi
                b=$(count "${args[@]}" --passes=$((2 * passes)))
                per=$(awk -v a="$a" -v b="$b" 'BEGIN { split(a, x, " "); split(b, y, " ");
                    printf "%.1f", (y[1] - x[1]) / (y[2] - x[2]) }')
                chk=""
                if [ "$check" -eq 1 ]; then
                    c=$(count "${args[@]}" --passes=$((4 * passes)))
                    chk=$(awk -v a="$b" -v b="$c" 'BEGIN { split(a, x, " "); split(b, y, " ");
                        printf "%.1f", (y[1] - x[1]) / (y[2] - x[2]) }')
                fi
                line+=$(printf " %${w}s" "$per${chk:+/$chk}")
                echo "$s,$isa,$d,$f,$passes,${a%% *},${b%% *},$per,$chk" >>"$csv"
            done
            echo "$line"
        done
    done
done
echo
printf '%s\n' "- textbook: the auto-vectorized peer of the same ISA (bench/peer/naive.c); it has one" \
    "  contract, normals always, so only its normal column is filled."
[ "$check" -eq 1 ] && echo "- a/b: N -> 2N passes / 2N -> 4N passes"
if ((${#notes[@]})); then
    printf -- '- %s\n' "${notes[@]}"
fi
echo "icount.sh: $((SECONDS - start)) s; $csv"
