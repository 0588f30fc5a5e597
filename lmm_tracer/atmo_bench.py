#!/usr/bin/env python3
"""The reference renderer in the atmosphere: its measured error and speed,
the figures docs/lmm.md ("The atmosphere") quotes.

    python3 lmm_tracer/atmo_bench.py [--build-dir build] [--size 160x120]
        [--spp 4,16,64]

Prints, from the tests' own output (core/sh_atmosphere_test and
core/sh_reference_atmo_test, which compare with independent quadratures),
the largest relative error of the optical depth and of each converged pixel;
then, for scenes/sky_sunset.json and scenes/earth_from_space.json rendered
by `lmm_tracer --mode reference --threads 1` at each spp, the CPU seconds
of the run (getrusage of the child: honest on a loaded machine, where the
wall clock is not), the CPU time per in-scattering sample, and the image's
own noise as lmm_tracer estimates it (relative RMS). Standard library only.
"""

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_test(build, name):
    """A test's stderr lines (it prints its measured differences)."""
    exe = build / "core" / name
    p = subprocess.run([str(exe)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, check=False)
    if p.returncode != 0:
        sys.exit("atmo_bench: %s failed:\n%s" % (name, p.stdout))
    return p.stdout.splitlines()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--spp", default="4,16,64")
    args = ap.parse_args()
    build = Path(args.build_dir).resolve()
    width, height = (int(v) for v in args.size.split("x"))
    spps = [int(v) for v in args.spp.split(",")]

    print("machine: %d cores, %s" % (os.cpu_count(), next(
        (l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")),
        "?")))
    print("load average: %.1f" % os.getloadavg()[0])
    print()
    print("Error against independent quadrature")
    for line in run_test(build, "sh_atmosphere_test"):
        if "largest relative error" in line:
            print("  " + line.strip())
    worst = {}
    for line in run_test(build, "sh_reference_atmo_test"):
        m = re.match(r"(.*), channel \d: .*relative difference ([0-9.e+-]+)\)", line)
        if m:
            worst[m.group(1)] = max(worst.get(m.group(1), 0.0), float(m.group(2)))
    print("  reference, one pixel at 20000 samples, largest channel difference:")
    for view, d in worst.items():
        print("    %-45s %.1e" % (view, d))
    print()
    print("Speed: lmm_tracer --mode reference --threads 1 at %dx%d" % (width, height))
    print("  %-18s %6s %10s %14s %12s" % ("scene", "spp", "CPU s", "us / sample", "noise"))
    tool = build / "lmm_tracer" / "lmm_tracer"
    with tempfile.TemporaryDirectory(prefix="atmo_bench.") as tmp:
        for scene in ("sky_sunset", "earth_from_space"):
            for spp in spps:
                stats = Path(tmp) / "stats.json"
                before = child_cpu()
                subprocess.run([str(tool), str(ROOT / "scenes" / (scene + ".json")),
                                "--mode", "reference", "--width", str(width),
                                "--height", str(height), "--spp", str(spp), "--threads", "1",
                                "-q", "-o", str(Path(tmp) / "out.exr"), "--stats", str(stats)],
                               check=True)
                cpu = child_cpu() - before
                s = json.loads(stats.read_text())
                print("  %-18s %6d %10.2f %14.2f %11.2f%%" % (
                    scene, spp, cpu, 1e6 * cpu / max(1, s["medium_samples"]),
                    100 * s.get("noise_rel_rms_estimate", 0.0)))


if __name__ == "__main__":
    main()
