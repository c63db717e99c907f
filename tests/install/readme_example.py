#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""readme_example.py - writes the first (or the N-th) ```c block of README.md to a C file.

Usage: readme_example.py README.md out.c [N]

The README promises an example that compiles as written; the build compiles this file
against the library and a test runs it. Without such a block, or when the block has no
main(), the file is a program that says so and fails: the test fails, and the rest of
the build goes on.
"""
import re
import sys


def main():
    readme, out = sys.argv[1:3]
    nth = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    text = open(readme, encoding='utf-8').read()
    blocks = list(re.finditer(r'^```c[ \t]*\n(.*?)^```[ \t]*$', text, flags=re.S | re.M))
    m = blocks[nth - 1] if len(blocks) >= nth else None
    if m and re.search(r'\bmain\s*\(', m.group(1)):
        code = f'#line {text.count(chr(10), 0, m.start(1)) + 1} "README.md"\n' + m.group(1)
    else:
        why = 'is not a complete program (no main)' if m else 'is missing'
        code = ('#include <stdio.h>\n'
                'int main(void)\n{\n'
                f'    puts("README.md: ```c block {nth} {why}");\n'
                '    return 1;\n}\n')
    with open(out, 'w', encoding='utf-8') as f:
        f.write(code)
    return 0


if __name__ == '__main__':
    sys.exit(main())
