#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/embree/mirror-prefix.sh PREFIX DEST - DEST becomes a view of the Embree install
# PREFIX (symlinks into it) in which every library symlink is a symlink again.
#
# A tree copied by a tool that does not keep symlinks (an archive extracted without
# them, a copy onto a file system without them) turns libembree4.so -> libembree4.so.4
# into a file holding the text "libembree4.so.4": the linker then reads text, and the
# loader cannot find the soname. Here such a file (small, naming a file beside it)
# becomes the link it was; everything else in PREFIX/lib and PREFIX/lib64 is linked as
# it is, and the other top-level entries (include, share) are linked whole. CMake's
# package finds its library relative to its own directory, which stays under DEST.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 PREFIX DEST" >&2; exit 2; }
prefix=$(cd "$1" && pwd)
dest=$2
rm -rf "$dest"
mkdir -p "$dest"
for entry in "$prefix"/*; do
    name=$(basename "$entry")
    case $name in
    lib | lib64) ;;
    *)
        ln -s "$entry" "$dest/$name"
        continue
        ;;
    esac
    mkdir -p "$dest/$name"
    for f in "$entry"/*; do
        base=$(basename "$f")
        target=""
        if [ -f "$f" ] && [ ! -L "$f" ] && [ "$(stat -c %s "$f")" -lt 256 ]; then
            target=$(head -c 255 "$f" | tr -d '\n')
            case $target in
            */* | "") target="" ;;
            *) [ -e "$entry/$target" ] || target="" ;;
            esac
        fi
        if [ -n "$target" ]; then
            ln -s "$target" "$dest/$name/$base"
        else
            ln -s "$f" "$dest/$name/$base"
        fi
    done
done
