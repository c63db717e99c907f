#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""stores_same.py OUTHASH - every answer the same under every store policy.

The store policies (CYLRAY_STORES: masked, blend, lanes) differ only in how a vector of
hits reaches memory; outhash hashes every answer of every path, width, flag set and
leaf, so its output must not change with the policy. Exit 0 when the three agree."""
import os
import subprocess
import sys


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[0])
        return 2
    out = {}
    for policy in ("masked", "blend", "lanes"):
        env = dict(os.environ, CYLRAY_STORES=policy)
        run = subprocess.run([sys.argv[1]], env=env, capture_output=True, text=True)
        if run.returncode != 0:
            print(f"outhash failed under CYLRAY_STORES={policy}: {run.stderr.strip()}")
            return 1
        out[policy] = run.stdout
        print(f"CYLRAY_STORES={policy}: {run.stdout.strip().splitlines()[-1]}")
    if len(set(out.values())) != 1:
        print("FAIL: the answers depend on the store policy")
        return 1
    print("ok: the same answers under every store policy")
    return 0


if __name__ == "__main__":
    sys.exit(main())
