#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""fast_same.py OUTHASH - CYLRAY_FAST served by the exact kernels where the CPU divides quickly.

Under CYLRAY_ESTIMATES=off (the choice on AMD's and Hygon's cores), every x86 path answers
a call with CYLRAY_FAST exactly as the same call without it: outhash must then give, for
each of those paths, the hash of `outhash --fast-plain`, which makes every call without
the flag. Under CYLRAY_ESTIMATES=on the flag sets without FAST keep their answers. Unset,
the library chooses by vendor: the exact kernels on AMD and Hygon, the estimates on any
other CPU (read from /proc/cpuinfo where there is one). Exit 0 when all three hold."""
import os
import subprocess
import sys

X86 = ("sse41", "avx2", "avx512")


def vendor():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("vendor_id"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return None


def run(exe, estimates, *args):
    env = dict(os.environ, CYLRAY_ESTIMATES=estimates)
    if estimates is None:
        del env["CYLRAY_ESTIMATES"]
    out = subprocess.run([exe, *args], env=env, capture_output=True, text=True)
    if out.returncode != 0:
        print(f"outhash {' '.join(args)} failed under CYLRAY_ESTIMATES={estimates}: "
              f"{out.stderr.strip()}")
        sys.exit(1)
    return dict(line.split() for line in out.stdout.splitlines())


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[0])
        return 2
    exe = sys.argv[1]
    divided, plain = run(exe, "off"), run(exe, "off", "--fast-plain")
    paths = [isa for isa in X86 if isa in divided]
    bad = [isa for isa in paths if divided[isa] != plain[isa]]
    for isa in paths:
        print(f"{isa}: FAST {divided[isa]}, without it {plain[isa]}")
    if bad:
        print(f"FAIL: with CYLRAY_ESTIMATES=off, FAST differs from the exact kernels on {bad}")
        return 1
    if run(exe, "on", "--no-fast") != run(exe, "off", "--no-fast"):
        print("FAIL: CYLRAY_ESTIMATES changed answers without CYLRAY_FAST")
        return 1
    v = vendor()
    if v is not None and paths:
        divides = v in ("AuthenticAMD", "HygonGenuine")
        chosen = run(exe, None)
        expect = divided if divides else run(exe, "on")
        if any(chosen[isa] != expect[isa] for isa in paths):
            print(f"FAIL: on {v} FAST should take the "
                  f"{'exact kernels' if divides else 'estimates'} by default")
            return 1
        print(f"{v}: FAST by the {'exact kernels' if divides else 'estimates'} by default")
    print(f"ok: FAST by the exact kernels on {', '.join(paths) or 'no x86 path here'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
