#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/run.sh - build and run the test suite: by default the gcc release build (what
# users install); with `all`, every configuration CI needs. Installs whatever tools are
# missing first, and ends with the line
#     N passed, N failed
# counted from each build's meson-logs/testlog.json (meson test's exit status is the
# failure count modulo 256) plus the timed fuzzing run. Exits nonzero when anything
# failed, a build included.
#
# Configurations, each in its own build directory build/test-<name>:
#   gcc-release    gcc, release (-O3, what the README's install line builds),
#                  warnings are errors, no bench: the whole suite
#   clang-release  clang, release, warnings are errors, no bench: the whole suite (with
#                  the fuzz corpus and a short deterministic libFuzzer session); every
#                  answer of outhash bit for bit the gcc-release build's
#   estimates  gcc, -O2 (no debug information), -Destimate=runtime: every answer of outhash
#            bit for bit the gcc-release build's (another optimisation level, the
#            hardware's estimates); then each stand-in for the hardware's reciprocal
#            and reciprocal-square-root estimates (exact, high, low, table: what another
#            vendor's CPU may give; src/simd/estimate.h) in turn: that it changes
#            FAST's answers on every x86 path (it is in effect), CYLRAY_FAST's accuracy
#            (cylcheck, leafcheck) on every x86 path, and every answer of the other flag
#            sets bit for bit (outhash --no-fast), so that a run on one CPU speaks for
#            every CPU of its ISA
#   asan     clang, -O2 with line tables, AddressSanitizer + UndefinedBehaviorSanitizer:
#            the whole suite, and every answer of outhash bit for bit the gcc-release
#            build's; the library is also built with libFuzzer coverage, so the fuzz
#            step reuses this build
#   aarch64  cross-compiled for AArch64 (NEON), -O2, gcc's ASan + UBSan, under qemu-user
#   tsan     clang with ThreadSanitizer, the thread test only
#   fuzz     libFuzzer on the asan build's target: FUZZ_RUNS inputs (6000) from seed
#            FUZZ_SEED (1), so that a commit's result does not depend on the clock;
#            FUZZ_SECONDS (120) caps the time. FUZZ_SEED=0 seeds from the clock, and
#            tests/fuzz/run-long.sh explores for as long as one likes.
#   embree-extra  the Embree adapter against each further Embree install prefix in
#            CYLRAY_EMBREE_PREFIXES (colon-separated, e.g. an Embree 4 beside the
#            distribution's Embree 3; empty: skipped): gcc, release, -Dembree_prefix,
#            only the library and the embree suite: the adapter's tests and those of
#            an installed adapter (its exports, pkg-config and CMake consumers, the
#            README's example), in build/test-embree-<N>. The other
#            configurations test whichever Embree the system has.
# Not in `all`, for whoever wants the whole suite at -O2:
#   gcc, clang  debugoptimized, warnings are errors, the whole suite. Their answers are
#            the release builds' (estimates and asan show it for gcc and clang), and
#            what the suite checks beyond answers runs in the release and asan builds.
# Sanitizer and qemu configurations set CYLRAY_TEST_QUICK=1 so that heavy tests shrink.
# Why asan and fuzz share a build: the kernels are stamped out in hundreds of flag
# specialisations per ISA, and a sanitized build of them costs about ten CPU minutes;
# one build serves both.
#
# Usage: tests/run.sh                  gcc-release alone: what users install, in minutes
#        tests/run.sh all              the whole matrix above (what .ci/run runs)
#        tests/run.sh [config...]      e.g. tests/run.sh gcc clang
# Environment: FUZZ_RUNS, FUZZ_SEED, FUZZ_SECONDS, CYLRAY_EMBREE_PREFIXES (above);
# CI=true makes a configuration whose tools cannot be installed count as failed instead
# of skipped.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
ALL_CONFIGS=(gcc-release clang-release estimates asan aarch64 tsan fuzz embree-extra)
CYLRAY_EMBREE_PREFIXES=${CYLRAY_EMBREE_PREFIXES:-}
FUZZ_SECONDS=${FUZZ_SECONDS:-120}
FUZZ_RUNS=${FUZZ_RUNS:-6000}
FUZZ_SEED=${FUZZ_SEED:-1}
CI=${CI:-}

# ---- which configurations -------------------------------------------------------
CONFIGS=()
for a in "$@"; do
    case "$a" in
    -h | --help)
        sed -n '3,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'
        exit 0
        ;;
    gcc | clang | gcc-release | clang-release | estimates | asan | aarch64 | tsan | fuzz | embree-extra)
        CONFIGS+=("$a")
        ;;
    all)
        CONFIGS+=("${ALL_CONFIGS[@]}")
        ;;
    *)
        echo "run.sh: unknown configuration '$a' (known: ${ALL_CONFIGS[*]} gcc clang)" >&2
        exit 2
        ;;
    esac
done
[ ${#CONFIGS[@]} -gt 0 ] || CONFIGS=(gcc-release)
wants() {
    local c
    for c in "${CONFIGS[@]}"; do [ "$c" = "$1" ] && return 0; done
    return 1
}

# ---- tools: check, then install what is missing ---------------------------------
# Each check names the Debian package that provides it.
missing_pkgs=()
need() { # need <package> <test command...>
    local pkg=$1
    shift
    if ! "$@" >/dev/null 2>&1; then
        missing_pkgs+=("$pkg")
    fi
}
have_fuzzer_rt() {
    command -v clang >/dev/null || return 1
    local rt
    rt=$(clang -print-resource-dir)/lib/linux/libclang_rt.fuzzer-x86_64.a
    [ -e "$rt" ] || [ -e "$(clang -print-resource-dir)/lib/x86_64-unknown-linux-gnu/libclang_rt.fuzzer.a" ]
}
have_cxx() { command -v c++ || command -v g++ || command -v clang++; }

need meson command -v meson
need ninja-build command -v ninja
need python3 command -v python3
if wants gcc || wants gcc-release || wants estimates || wants embree-extra; then
    need gcc command -v gcc
fi
if wants clang || wants clang-release || wants asan || wants tsan || wants fuzz; then
    need clang command -v clang
fi
if wants clang || wants asan || wants tsan || wants fuzz; then
    need libclang-rt-14-dev have_fuzzer_rt
fi
if wants aarch64; then
    need gcc-aarch64-linux-gnu command -v aarch64-linux-gnu-gcc
    need libc6-dev-arm64-cross test -e /usr/aarch64-linux-gnu/include/stdio.h
    need qemu-user command -v qemu-aarch64
fi
# The header's C++ test needs some C++ compiler, and the tests of an installed tree
# cmake and pkg-config; each is skipped (not failed) without.
if wants gcc || wants clang || wants gcc-release || wants clang-release || wants embree-extra; then
    need g++ have_cxx
    need cmake command -v cmake
    need pkgconf command -v pkg-config
fi

if [ ${#missing_pkgs[@]} -gt 0 ]; then
    # dedupe, keep order
    mapfile -t missing_pkgs < <(printf '%s\n' "${missing_pkgs[@]}" | awk '!seen[$0]++')
    echo "== installing: ${missing_pkgs[*]}"
    SUDO=()
    if [ "$(id -u)" -ne 0 ]; then
        if command -v sudo >/dev/null; then SUDO=(sudo -n); else SUDO=(false); fi
    fi
    if "${SUDO[@]}" apt-get update -q >/dev/null &&
        "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q \
            --no-install-recommends "${missing_pkgs[@]}" >/dev/null; then
        echo "   installed"
    else
        echo "   could not install (no root, or apt failed); configurations that need them will not run"
    fi
fi

# ---- running one configuration ---------------------------------------------------
PASSED=0
FAILED=0
SUMMARY=()
TSTART=$(date +%s)

# Counts results in a testlog.json; prints "passed failed".
count_log() {
    python3 - "$1" <<'PY'
import json, sys
passed = failed = 0
for line in open(sys.argv[1], encoding='utf-8', errors='replace'):
    line = line.strip()
    if not line:
        continue
    r = json.loads(line).get('result')
    if r == 'OK':
        passed += 1
    elif r in ('FAIL', 'ERROR', 'TIMEOUT', 'UNEXPECTEDPASS'):
        failed += 1
print(passed, failed)
PY
}

note() { # note <config> <passed> <failed> <seconds> <remark>
    PASSED=$((PASSED + $2))
    FAILED=$((FAILED + $3))
    SUMMARY+=("$(printf '%-13s %4d passed %4d failed %6ss  %s' "$1" "$2" "$3" "$4" "$5")")
    printf -- '-- %s: %d passed, %d failed (%ss) %s\n' "$1" "$2" "$3" "$4" "$5"
}

# A configuration whose tools are missing: skipped locally, a failure in CI.
unavailable() { # unavailable <config> <what is missing>
    if [ "$CI" = true ]; then
        note "$1" 0 1 0 "FAILED: $2 missing"
    else
        SUMMARY+=("$(printf '%-13s skipped: %s missing' "$1" "$2")")
        echo "-- $1: skipped ($2 missing)"
    fi
}

# setup_build <dir> <meson setup args...>: configures (or reconfigures) and builds.
# Targets to build may be given in BUILD_TARGETS (default: all).
setup_build() {
    local dir=$1
    shift
    if [ -e "$dir" ] && [ ! -e "$dir/meson-private/coredata.dat" ]; then rm -rf "$dir"; fi
    if [ -e "$dir/meson-private/coredata.dat" ]; then
        meson setup --reconfigure "$dir" "$@" >"$dir.setup.log" 2>&1 || {
            tail -30 "$dir.setup.log"
            return 1
        }
    else
        mkdir -p "$(dirname "$dir")"
        meson setup "$dir" "$@" >"$dir.setup.log" 2>&1 || {
            tail -30 "$dir.setup.log"
            return 1
        }
    fi
    # shellcheck disable=SC2086
    ninja -C "$dir" ${BUILD_TARGETS:-} >"$dir.build.log" 2>&1 || {
        grep -E 'error|FAILED' "$dir.build.log" | head -30
        return 1
    }
}

# run_tests <config> <dir> <start time> <meson test args...>: runs the suite with the
# environment in TEST_ENV (an array of VAR=value) and counts the results.
TEST_ENV=()
run_tests() {
    local cfg=$1 dir=$2 t0=$3 remark=""
    shift 3
    # meson names its log after a --wrapper (testlog-setarch.json): take whichever appears
    rm -f "$dir"/meson-logs/testlog*.json
    env "${TEST_ENV[@]}" meson test -C "$dir" --no-rebuild --print-errorlogs "$@" \
        >"$dir.test.log" 2>&1 || true
    grep -E '^ *[0-9]+/[0-9]+ ' "$dir.test.log" | sed 's/^/   /' || true
    local log p f
    log=$(ls -t "$dir"/meson-logs/testlog*.json 2>/dev/null | head -1 || true)
    if [ -z "$log" ] || [ ! -s "$log" ]; then
        note "$cfg" 0 1 $(($(date +%s) - t0)) "FAILED: no test results ($dir.test.log)"
        return
    fi
    read -r p f < <(count_log "$log")
    if [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then
        f=1
        remark="FAILED: no test ran"
    fi
    if [ "$f" -gt 0 ]; then
        # the failing tests' own output, for the CI log
        awk '/^=+ [0-9]+\/[0-9]+ =+$/ {show = 0} /^[ ]*[0-9]+\/[0-9]+ .*(FAIL|ERROR|TIMEOUT)/ {show = 1} show' \
            "$dir.test.log" | head -150
        remark="${remark:-see $dir.test.log}"
    fi
    note "$cfg" "$p" "$f" $(($(date +%s) - t0)) "$remark"
}

# What the sanitizers must do on a finding: stop, so that the test fails.
san_env() { # san_env <extra ASAN_OPTIONS>
    TEST_ENV=("ASAN_OPTIONS=$1halt_on_error=1:abort_on_error=1:print_summary=1"
        "UBSAN_OPTIONS=halt_on_error=1:abort_on_error=1:print_stacktrace=1:print_summary=1"
        "TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1")
}

build_failed() { # build_failed <config> <dir> <start time>
    note "$1" 0 1 $(($(date +%s) - $3)) "FAILED: build (see $2.setup.log, $2.build.log)"
}

config_gcc() {
    local t0 dir=build/test-gcc
    t0=$(date +%s)
    command -v gcc >/dev/null || { unavailable gcc gcc; return; }
    TEST_ENV=()
    if CC=gcc CXX=g++ setup_build "$dir" --buildtype=debugoptimized --werror; then
        run_tests gcc "$dir" "$t0"
    else
        build_failed gcc "$dir" "$t0"
    fi
}

config_clang() {
    local t0 dir=build/test-clang
    t0=$(date +%s)
    command -v clang >/dev/null || { unavailable clang clang; return; }
    san_env "" # the fuzz target in this build carries ASan and UBSan
    if CC=clang CXX=clang++ setup_build "$dir" --buildtype=debugoptimized --werror; then
        run_tests clang "$dir" "$t0"
    else
        build_failed clang "$dir" "$t0"
    fi
}

# The release builds: what users install (-O3), whose optimiser transforms what
# debugoptimized's -O2 leaves alone; every test runs there as well.
config_release() { # config_release <name> <cc> <cxx>
    local t0 dir=build/test-$1
    t0=$(date +%s)
    command -v "$2" >/dev/null || { unavailable "$1" "$2"; return; }
    san_env "" # clang's fuzz target, if built, carries ASan and UBSan
    if CC=$2 CXX=$3 setup_build "$dir" --buildtype=release --werror -Dbench=false; then
        run_tests "$1" "$dir" "$t0"
        [ "$1" = gcc-release ] && GCC_RELEASE_BUILT=1
        same_bits "$1" "$dir"
    else
        build_failed "$1" "$dir" "$t0"
    fi
}
# The library's answers do not depend on the compiler nor on the optimisation level:
# every path, width, flag set (CYLRAY_FAST included) and leaf hashed by outhash, bit for
# bit as the gcc release build's, where that was built earlier in the same run.
GCC_RELEASE_BUILT=0
REF_OUTHASH=build/test-gcc-release/tests/check/outhash
same_bits() { # same_bits <config> <dir>
    [ "$1" != gcc-release ] && [ "$GCC_RELEASE_BUILT" = 1 ] && [ -x "$2/tests/check/outhash" ] ||
        return 0
    if [ "$(env "${TEST_ENV[@]}" "$2/tests/check/outhash")" = "$("$REF_OUTHASH")" ]; then
        note "$1" 1 0 0 "outhash: the gcc release build's answers bit for bit"
    else
        note "$1" 0 1 0 "FAILED: outhash differs from the gcc release build's"
    fi
}
config_gcc-release() { config_release gcc-release gcc g++; }
config_clang-release() { config_release clang-release clang clang++; }

# CYLRAY_FAST takes the hardware's estimates, whose tables differ between vendors
# (rcpps, rsqrtps); nothing else does. One build takes its stand-in from the
# environment: with the hardware's, its answers are the gcc release build's (at -O2);
# with each stand-in, FAST's accuracy is checked on every path, and the other flag sets
# answer bit for bit as the hardware build.
config_estimates() {
    local t0 ref="" v dir=build/test-estimates p=0 f=0 c ff log
    t0=$(date +%s)
    command -v gcc >/dev/null || { unavailable estimates gcc; return; }
    TEST_ENV=()
    if [ "$GCC_RELEASE_BUILT" = 1 ] || CC=gcc CXX=g++ BUILD_TARGETS=tests/check/outhash \
        setup_build build/test-gcc-release --buildtype=release --werror -Dbench=false; then
        GCC_RELEASE_BUILT=1
        ref=$("$REF_OUTHASH" --no-fast)
    fi
    if [ -z "$ref" ] || ! CC=gcc CXX=g++ \
        BUILD_TARGETS="tests/check/cylcheck tests/check/leafcheck tests/check/outhash" \
        setup_build "$dir" -Doptimization=2 -Ddebug=false --werror -Dbench=false -Destimate=runtime; then
        build_failed estimates "$dir" "$t0"
        return
    fi
    same_bits estimates "$dir"
    # FAST's answers with the hardware's estimates, per x86 path: each stand-in must
    # change them on every one, or the checks below would judge the hardware's again
    local hw same
    hw=$(CYLRAY_ESTIMATES=on "$dir/tests/check/outhash" | grep -E '^(sse41|avx2|avx512) ')
    for v in exact high low table; do
        if [ "$(CYLRAY_TEST_ESTIMATE=$v "$dir/tests/check/outhash" --no-fast)" = "$ref" ]; then
            p=$((p + 1))
        else
            echo "   $v: the answers without CYLRAY_FAST differ from the hardware build's"
            f=$((f + 1))
        fi
        same=$(CYLRAY_TEST_ESTIMATE=$v CYLRAY_ESTIMATES=on "$dir/tests/check/outhash" |
            grep -Fxf <(echo "$hw") || true)
        if [ -z "$hw" ] || [ -n "$same" ]; then
            echo "   $v: the stand-in is not in effect on: ${same:-every path}"
            f=$((f + 1))
        else
            p=$((p + 1))
        fi
        rm -f "$dir"/meson-logs/testlog*.json
        # the stand-ins, also where the CPU would serve FAST with the exact kernels
        CYLRAY_TEST_ESTIMATE=$v CYLRAY_ESTIMATES=on meson test -C "$dir" --no-rebuild \
            --print-errorlogs cylcheck-estimates leafcheck >"$dir.$v.test.log" 2>&1 || true
        log=$(ls -t "$dir"/meson-logs/testlog*.json 2>/dev/null | head -1 || true)
        if [ -z "$log" ]; then
            echo "   $v: no test results ($dir.$v.test.log)"
            f=$((f + 1))
            continue
        fi
        read -r c ff < <(count_log "$log")
        echo "   $v: outhash --no-fast as the hardware build's; cylcheck, leafcheck: $c passed, $ff failed"
        [ "$ff" -eq 0 ] || grep -E '^FAIL|^headline.*FAIL|missed' "$dir.$v.test.log" | head -20 | sed 's/^/     /'
        p=$((p + c)) f=$((f + ff))
    done
    note estimates "$p" "$f" $(($(date +%s) - t0)) "$([ "$f" -eq 0 ] || echo "see $dir.*.test.log")"
}

# The clang ASan + UBSan build, with libFuzzer coverage in every object. Targets to
# build: all, or those in BUILD_TARGETS.
ASAN_DIR=build/test-asan
# -O2 with line tables only: a report still names file and line, and the kernels'
# hundreds of specialisations compile in about two thirds of the time full debug
# information takes (avx2.c: 100 s against 150 s with -g, clang 14, Zen 5).
setup_asan() {
    CC=clang CXX=clang++ setup_build "$ASAN_DIR" -Doptimization=2 -Ddebug=false \
        -Db_sanitize=address,undefined -Db_lundef=false \
        "-Dc_args=-fsanitize=fuzzer-no-link -gline-tables-only" -Dbench=false
}

config_asan() {
    local t0
    t0=$(date +%s)
    command -v clang >/dev/null || { unavailable asan clang; return; }
    san_env "detect_leaks=1:"
    TEST_ENV+=(CYLRAY_TEST_QUICK=1)
    if setup_asan; then
        ASAN_STATE=built
        run_tests asan "$ASAN_DIR" "$t0" --timeout-multiplier 3
        same_bits asan "$ASAN_DIR"
    else
        ASAN_STATE=failed
        build_failed asan "$ASAN_DIR" "$t0"
    fi
}

config_aarch64() {
    local t0 dir=build/test-aarch64
    t0=$(date +%s)
    command -v aarch64-linux-gnu-gcc >/dev/null || { unavailable aarch64 aarch64-linux-gnu-gcc; return; }
    command -v qemu-aarch64 >/dev/null || { unavailable aarch64 qemu-aarch64; return; }
    # LeakSanitizer cannot run under qemu-user; ASan and UBSan can.
    san_env "detect_leaks=0:"
    TEST_ENV+=(CYLRAY_TEST_QUICK=1)
    # -O2 without debug information: -g took 40 % of this build's time (a finding's
    # stack shows the functions; its lines are for a local build to show).
    if setup_build "$dir" --cross-file tests/cross/aarch64-linux-gnu.ini \
        -Doptimization=2 -Ddebug=false -Db_sanitize=address,undefined -Dbench=false; then
        run_tests aarch64 "$dir" "$t0" --timeout-multiplier 10
    else
        build_failed aarch64 "$dir" "$t0"
    fi
}

config_tsan() {
    local t0 dir=build/test-tsan wrap=()
    t0=$(date +%s)
    command -v clang >/dev/null || { unavailable tsan clang; return; }
    san_env ""
    # ThreadSanitizer needs a low-entropy address layout on some kernels (high
    # vm.mmap_rnd_bits): run without randomisation where setarch allows it.
    if setarch "$(uname -m)" -R true 2>/dev/null; then
        wrap=(--wrapper "setarch $(uname -m) -R")
    fi
    if CC=clang BUILD_TARGETS=tests/robust/robust_threads setup_build "$dir" \
        -Doptimization=1 -Ddebug=true -Db_sanitize=thread -Db_lundef=false \
        -Dbench=false; then
        run_tests tsan "$dir" "$t0" --suite threads --timeout-multiplier 5 "${wrap[@]}"
    else
        build_failed tsan "$dir" "$t0"
    fi
}

config_fuzz() {
    local t0 dir=$ASAN_DIR
    t0=$(date +%s)
    command -v clang >/dev/null || { unavailable fuzz clang; return; }
    have_fuzzer_rt || { unavailable fuzz "libFuzzer (libclang-rt-14-dev)"; return; }
    if [ "${ASAN_STATE:-}" = failed ]; then
        note fuzz 0 1 0 "FAILED: the asan build it needs failed"
        return
    fi
    if [ -z "${ASAN_STATE:-}" ] && ! BUILD_TARGETS=tests/fuzz/cylray_fuzz setup_asan; then
        build_failed fuzz "$dir" "$t0"
        return
    fi
    if [ ! -x "$dir/tests/fuzz/cylray_fuzz" ]; then
        note fuzz 0 1 $(($(date +%s) - t0)) "FAILED: no libFuzzer target was built"
        return
    fi
    local work=$dir/fuzz-corpus art=$dir/fuzz-artifacts/ log=build/test-fuzz.log
    mkdir -p "$work" "$art"
    san_env "detect_leaks=1:"
    echo "   fuzzing: $FUZZ_RUNS inputs, seed $FUZZ_SEED, at most ${FUZZ_SECONDS}s (corpus $work, crashes to $art)"
    if env "${TEST_ENV[@]}" "$dir/tests/fuzz/cylray_fuzz" -runs="$FUZZ_RUNS" -seed="$FUZZ_SEED" \
        -max_total_time="$FUZZ_SECONDS" -timeout=20 -max_len=1024 -print_final_stats=1 -artifact_prefix="$art" \
        "$work" tests/fuzz/corpus >"$log" 2>&1; then
        grep -E '^cylray-fuzz: executions|stat::number_of_executed_units' "$log" | sed 's/^/   /'
        note fuzz 1 0 $(($(date +%s) - t0)) ""
    else
        grep -E '^cylray-fuzz|^  |^==[0-9]+==|SUMMARY|Test unit written' "$log" |
            head -60 | sed 's/^/   /'
        # the case and the input once more, last, where the tail of a long log shows them
        { grep -E '^cylray-fuzz: ' "$log" | head -6; grep -E 'Test unit written|^Base64: ' "$log"; } |
            sed 's/^/   /'
        note fuzz 0 1 $(($(date +%s) - t0)) "FAILED: see $log"
    fi
}

# The adapter against each extra Embree prefix. The prefix is seen through a mirror
# (tests/embree/mirror-prefix.sh) whose library symlinks are links, whatever copy of
# the tree it is; the build is limited to what the embree and install suites run (the
# libraries, which the install tests stage, and those suites' programs).
config_embree-extra() {
    local t0 prefix n=0 dir mirror targets
    t0=$(date +%s)
    if [ -z "$CYLRAY_EMBREE_PREFIXES" ]; then
        SUMMARY+=("$(printf '%-13s skipped: CYLRAY_EMBREE_PREFIXES is empty' embree-extra)")
        echo "-- embree-extra: skipped (CYLRAY_EMBREE_PREFIXES is empty)"
        return
    fi
    TEST_ENV=()
    local IFS_old=$IFS
    IFS=:
    # shellcheck disable=SC2206 # split on the colons on purpose
    local prefixes=($CYLRAY_EMBREE_PREFIXES)
    IFS=$IFS_old
    for prefix in "${prefixes[@]}"; do
        [ -n "$prefix" ] || continue
        n=$((n + 1))
        t0=$(date +%s)
        mirror=$PWD/build/embree-prefix-$n
        dir=build/test-embree-$n
        echo "   $prefix"
        if ! tests/embree/mirror-prefix.sh "$prefix" "$mirror" >/dev/null 2>&1; then
            note "embree-extra" 0 1 0 "FAILED: cannot read $prefix"
            continue
        fi
        command -v gcc >/dev/null || { unavailable embree-extra gcc; continue; }
        if CC=gcc CXX=g++ BUILD_TARGETS=tests/embree/test_embree_agree setup_build "$dir" \
            --buildtype=release --werror -Dbench=false -Dembree=enabled \
            -Dembree_prefix="$mirror"; then
            targets=$(ninja -C "$dir" -t targets all | sed -n -E \
                's#^(src/(embree/)?lib[^/ ]*\.(so[.0-9]*|a)|tests/install/readme_example[0-9]+|tests/embree/test_embree_[a-z_]+): .*#\1#p')
            # shellcheck disable=SC2086 # one target a word
            if ninja -C "$dir" $targets >>"$dir.build.log" 2>&1; then
                grep -h 'cylray_embree:' "$dir.setup.log" | sed 's/^ */   /'
                run_tests "embree-extra" "$dir" "$t0" --suite embree
                continue
            fi
        fi
        build_failed "embree-extra" "$dir" "$t0"
    done
}

# ---- the run ----------------------------------------------------------------------
i=0
for cfg in "${CONFIGS[@]}"; do
    i=$((i + 1))
    case $cfg in
    gcc) what="gcc, debugoptimized, -Werror" ;;
    clang) what="clang, debugoptimized, -Werror" ;;
    gcc-release) what="gcc, release (-O3), -Werror" ;;
    clang-release) what="clang, release (-O3), -Werror" ;;
    estimates) what="gcc, -O2, the hardware's estimates, then other vendors' in their place (exact, high, low, table)" ;;
    asan) what="clang, ASan + UBSan (+ fuzzer coverage), CYLRAY_TEST_QUICK=1" ;;
    aarch64) what="aarch64 cross, NEON, ASan + UBSan under qemu-user, CYLRAY_TEST_QUICK=1" ;;
    tsan) what="clang, ThreadSanitizer, the thread test" ;;
    fuzz) what="libFuzzer + ASan + UBSan on the asan build, $FUZZ_RUNS inputs from seed $FUZZ_SEED" ;;
    embree-extra) what="gcc, release, the Embree adapter against ${CYLRAY_EMBREE_PREFIXES:-(no prefix)}" ;;
    esac
    echo "== [$i/${#CONFIGS[@]}] $cfg: $what"
    "config_$cfg"
done

echo
echo "== summary ($(($(date +%s) - TSTART))s in all)"
printf '   %s\n' "${SUMMARY[@]}"
echo "$PASSED passed, $FAILED failed"
[ "$FAILED" -eq 0 ]
