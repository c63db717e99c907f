#!/usr/bin/env bash
# bench/run.sh - builds cylray and the harness for release in their own build directory,
# runs every scenario once, and says where the tables, plots and image are.
#
#   bench/run.sh [harness options, e.g. --quick or --isa=avx2,avx512]
#
# Environment: CYLBENCH_BUILD (build directory, default build-bench/ at the top of the
# repository; not build/, which belongs to the main debug build), CYLBENCH_OUT (output
# directory, default bench/out), CC (compiler, read by meson at the first setup).
set -euo pipefail

start=$SECONDS
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$here")
build=${CYLBENCH_BUILD:-$root/build-bench}
out=${CYLBENCH_OUT:-$here/out}

# meson and ninja: installed from the distribution only when missing.
missing=()
command -v meson >/dev/null 2>&1 || missing+=(meson)
command -v ninja >/dev/null 2>&1 || missing+=(ninja-build)
if ((${#missing[@]})); then
    echo "run.sh: installing ${missing[*]} (apt-get)" >&2
    sudo=()
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null 2>&1 || {
            echo "run.sh: not root and no sudo: install ${missing[*]} first" >&2
            exit 1
        }
        sudo=(sudo)
    fi
    "${sudo[@]}" apt-get update -qq
    # env: sudo would drop DEBIAN_FRONTEND from the environment
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
        --no-install-recommends "${missing[@]}" >/dev/null
fi

# A release build (-O3, NDEBUG) without the test suite: the harness compiles the exact
# reference from tests/ref itself, so a test area under construction cannot stop it.
if [ -f "$build/build.ninja" ]; then
    meson configure "$build" -Dbuildtype=release -Dtests=false -Dbench=true >/dev/null
else
    meson setup "$build" "$root" -Dbuildtype=release -Dtests=false -Dbench=true >/dev/null
fi
ninja -C "$build" bench/cylbench >/dev/null
built=$SECONDS

mkdir -p "$out"
"$build/bench/cylbench" --out="$out" "$@"

echo
echo "run.sh: build $((built - start)) s, harness $((SECONDS - built)) s, total $((SECONDS - start)) s"
echo "run.sh: outputs in $out:"
for f in results.csv results.json table.txt time_vs_error.svg speedup.svg scene.png; do
    [ -e "$out/$f" ] && echo "  $out/$f"
done
