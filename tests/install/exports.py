#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""exports.py - the shared library exports exactly the functions cylray.h declares.

Usage: exports.py <cylray.h> <libcylray.so> [MACRO]

The declared names are read from the header (every declaration that carries CYLRAY_API,
or MACRO: CYLRAY_EMBREE_API for cylray_embree.h and libcylray_embree.so),
so the check follows the API as it grows. Fails on a dynamic symbol the header does not
declare (an internal kernel table or helper leaking out) and on a declared function the
library does not export. Exits 77 (skipped) where nm is missing.
"""
import re
import shutil
import subprocess
import sys

# Symbols the toolchain itself defines in every shared object, not the library's code.
LINKER_SYMBOLS = {'_init', '_fini', '_edata', '_end', '__bss_start'}


def declared(header, macro='CYLRAY_API'):
    text = open(header, encoding='utf-8').read()
    text = re.sub(r'/\*.*?\*/', ' ', text, flags=re.S)
    text = re.sub(r'//[^\n]*', ' ', text)
    text = re.sub(r'^\s*#[^\n]*(\\\n[^\n]*)*', ' ', text, flags=re.M)
    return set(re.findall(r'\b' + macro + r'\b[^;{}()]*?\b(cylray_\w+)\s*\(', text))


def exported(lib):
    out = subprocess.run(['nm', '-D', '--defined-only', lib], check=True,
                         capture_output=True, text=True).stdout
    names = set()
    for line in out.splitlines():
        fields = line.split()
        if len(fields) >= 2:
            names.add(fields[-1].split('@')[0])
    return names - LINKER_SYMBOLS


def main():
    header, lib = sys.argv[1:3]
    macro = sys.argv[3] if len(sys.argv) > 3 else 'CYLRAY_API'
    if shutil.which('nm') is None:
        print('exports: nm not found (binutils); skipped')
        return 77
    want = declared(header, macro)
    if not want:
        print(f'exports: no CYLRAY_API declaration found in {header}')
        return 1
    have = exported(lib)
    extra = sorted(have - want)
    missing = sorted(want - have)
    for name in extra:
        print(f'exported but not declared in {header}: {name}')
    for name in missing:
        print(f'declared in {header} but not exported: {name}')
    print(f'exports: {len(want)} declared, {len(have)} exported, '
          f'{len(extra)} extra, {len(missing)} missing')
    return 1 if extra or missing else 0


if __name__ == '__main__':
    sys.exit(main())
