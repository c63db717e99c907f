#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/format/check.sh - the tracked C sources and headers as .clang-format lays them
# out: clang-format --dry-run -Werror over `git ls-files '*.c' '*.h'`.
#
# Usage: tests/format/check.sh [SOURCE_ROOT [CLANG_FORMAT]]   (defaults: this tree,
# clang-format-14 or clang-format from PATH). Exits 0 when every file passes, 1 with
# the differences otherwise (`clang-format -i FILE` applies them), 77 (skipped) where
# it cannot judge: no git checkout, or a clang-format other than 14, the version the
# tree is laid out with (others break some lines differently from it).
set -euo pipefail

root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
cf=${2:-$(command -v clang-format-14 || command -v clang-format || true)}
if [ -z "$cf" ]; then
    echo "format: skipped, no clang-format"
    exit 77
fi
version=$("$cf" --version | head -1)
major=$(sed -n 's/.*clang-format version \([0-9]*\).*/\1/p' <<<"$version")
if [ "$major" != 14 ]; then
    echo "format: skipped, $cf is version ${major:-unknown}, not 14: $version"
    exit 77
fi
if ! command -v git >/dev/null || ! git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    echo "format: skipped, $root is not a git checkout"
    exit 77
fi

cd "$root"
mapfile -t files < <(git ls-files -- '*.c' '*.h')
if [ ${#files[@]} -eq 0 ]; then
    echo "format: no tracked C files under $root"
    exit 1
fi
if out=$("$cf" --dry-run -Werror "${files[@]}" 2>&1); then
    echo "format: ${#files[@]} files as .clang-format lays them out"
    exit 0
fi
printf '%s\n' "$out" | head -60
bad=$(printf '%s\n' "$out" | sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error:.*/\1/p' | sort -u)
echo "format: $(wc -l <<<"$bad") of ${#files[@]} files differ (clang-format -i FILE):"
while read -r f; do echo "  $f"; done <<<"$bad"
exit 1
