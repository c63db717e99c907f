#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bench/run.sh - builds cylray and the harness for release in their own build directory,
# runs every scenario once, and says where the tables, plots and image are.
#
#   bench/run.sh [harness options, e.g. --quick or --isa=avx2,avx512]
#
# Then, where Embree is present (Embree 4 or 3 on the system, or apt can install
# libembree-dev, or CYLBENCH_EMBREE_PREFIX names an install), the Embree comparison
# (bench/embree): cylray as Embree user geometry against that Embree's own curves. It
# says which Embree it was built against.
#
# Environment: CYLBENCH_BUILD (build directory, default build-bench/ at the top of the
# repository; not build/, which belongs to the main debug build), CYLBENCH_OUT (output
# directory, default bench/out), CC (compiler, read by meson at the first setup),
# CYLBENCH_EMBREE (the comparison's options, default --quick; e.g. --scene=molecule for
# one scene at full size; "off" skips it), CYLBENCH_EMBREE_PREFIX (an Embree install
# prefix to compare against, e.g. an Embree 4 in /opt/embree4; empty: the system's).
# Embree 4 and 3 need build directories of their own when both are compared.
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

# Embree 3 for the comparison: the distribution's package, only when missing, only where
# apt and root (or sudo) are at hand. Anything else skips the comparison, not the run.
embree_args=${CYLBENCH_EMBREE:---quick}
embree_prefix=${CYLBENCH_EMBREE_PREFIX:-}
embree_skip=""
if [ "$embree_args" = off ]; then
    embree_skip="CYLBENCH_EMBREE=off"
elif [ -n "$embree_prefix" ]; then
    # seen through a mirror whose library symlinks are links, however the tree was copied
    mirror=$build-embree-prefix
    "$root/tests/embree/mirror-prefix.sh" "$embree_prefix" "$mirror" ||
        embree_skip="cannot read $embree_prefix"
    embree_prefix=$mirror
elif [ ! -e /usr/include/embree3/rtcore.h ] && [ ! -e /usr/include/embree4/rtcore.h ]; then
    sudo=()
    [ "$(id -u)" -eq 0 ] || sudo=(sudo -n)
    if command -v apt-get >/dev/null 2>&1 &&
        { [ "$(id -u)" -eq 0 ] || sudo -n true 2>/dev/null; }; then
        echo "run.sh: installing libembree-dev for the Embree comparison" >&2
        "${sudo[@]}" apt-get update -qq || true
        "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
            --no-install-recommends libembree-dev >/dev/null ||
            embree_skip="apt-get could not install libembree-dev"
    else
        embree_skip="Embree is not installed and apt-get (as root or with sudo) is not available"
    fi
fi

# A release build (-O3, NDEBUG) without the test suite: the harness compiles the exact
# reference from tests/ref itself, so a test area under construction cannot stop it.
if [ -f "$build/build.ninja" ]; then
    meson configure "$build" -Dbuildtype=release -Dtests=false -Dbench=true \
        -Dembree_prefix="$embree_prefix" >/dev/null
else
    meson setup "$build" "$root" -Dbuildtype=release -Dtests=false -Dbench=true \
        -Dembree_prefix="$embree_prefix" >/dev/null
fi
ninja -C "$build" bench/cylbench >/dev/null
if [ -z "$embree_skip" ]; then
    if ninja -C "$build" -t targets all | grep -q '^bench/embree/cylembree:'; then
        ninja -C "$build" bench/embree/cylembree >/dev/null
    else
        embree_skip=$(grep -ho 'cylray_embree not built: .*' "$build/meson-logs/meson-log.txt" |
            tail -1)
        embree_skip=${embree_skip:-"meson did not build the adapter (see $build/meson-logs)"}
    fi
fi
built=$SECONDS

mkdir -p "$out"
"$build/bench/cylbench" --out="$out" "$@"

if [ -z "$embree_skip" ]; then
    embree_start=$SECONDS
    echo
    embree_used=$(sed -n 's/^#define CYLRAY_EMBREE_RTC_BUILT "\(.*\)".*/\1/p' \
        "$build/src/embree/config/cylray_embree_config.h")
    echo "run.sh: the Embree comparison (cylembree $embree_args) against Embree $embree_used" \
        "(${CYLBENCH_EMBREE_PREFIX:-installed on the system})"
    # shellcheck disable=SC2086 # the options are words on purpose
    "$build/bench/embree/cylembree" --out="$out" $embree_args
    echo "run.sh: Embree comparison $((SECONDS - embree_start)) s"
else
    echo
    echo "run.sh: skipping the Embree comparison: $embree_skip"
fi

echo
echo "run.sh: build $((built - start)) s, harness $((SECONDS - built)) s, total $((SECONDS - start)) s"
echo "run.sh: outputs in $out:"
for f in results.csv results.json table.txt time_vs_error.svg speedup.svg scene.png \
         embree.txt embree.csv; do
    [ -e "$out/$f" ] && echo "  $out/$f"
done
for f in "$out"/embree_*.png; do
    [ -e "$f" ] && echo "  $f"
done
exit 0
