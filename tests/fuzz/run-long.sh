#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/fuzz/run-long.sh - a long libFuzzer run of the kernel fuzz target.
#
# Usage: tests/fuzz/run-long.sh [seconds] [jobs]      (defaults: 3600 s, 2 jobs)
# Builds (or reuses) build/test-asan, the clang ASan + UBSan build with libFuzzer
# coverage that tests/run.sh also uses, then fuzzes with a corpus kept in
# build/fuzz-long/corpus (it grows from run to run; the seeds in tests/fuzz/corpus are
# read, never written). Crashes land in build/fuzz-long/artifacts/; replay one with
#     build/test-asan/tests/fuzz/cylray_fuzz build/fuzz-long/artifacts/crash-...
# which prints the case in hex floats. New interesting inputs worth keeping as seeds
# can be minimised into tests/fuzz/corpus with libFuzzer's -merge=1.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
seconds=${1:-3600}
jobs=${2:-2}
dir=build/test-asan
if [ ! -e "$dir/meson-private/coredata.dat" ]; then
    CC=clang CXX=clang++ meson setup "$dir" --buildtype=debugoptimized \
        -Db_sanitize=address,undefined -Db_lundef=false \
        -Dc_args=-fsanitize=fuzzer-no-link -Dbench=false
fi
ninja -C "$dir" tests/fuzz/cylray_fuzz
mkdir -p build/fuzz-long/corpus build/fuzz-long/artifacts
export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1
export UBSAN_OPTIONS=halt_on_error=1:abort_on_error=1:print_stacktrace=1
# -jobs runs that many fuzzing processes (their logs go to fuzz-<n>.log in the
# current directory, hence the cd); each stops at its first crash.
cd build/fuzz-long
exec "../../$dir/tests/fuzz/cylray_fuzz" -max_total_time="$seconds" -jobs="$jobs" \
    -workers="$jobs" -timeout=20 -max_len=1024 -print_final_stats=1 \
    -artifact_prefix=artifacts/ corpus ../../tests/fuzz/corpus
