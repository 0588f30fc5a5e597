#!/usr/bin/env python3
"""CTest: a target's renders of the test scenes agree with the reference.

  render_test.py --build BUILD pov|cycles|eevee

Exports every scene of scene_export/testdata that the target is tested on
(compare.TEST_SCENES), renders it with the real POV-Ray or Blender and with
the reference renderer, and checks compare.BOUNDS (see compare.py and
docs/scene_export.md for why they are what they are). EEVEE, slow under
xvfb-run with a software OpenGL, is held to a bound on the Lambert floor
only; its volumetric numbers are reported in the docs.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare  # noqa: E402


def main(argv):
    if len(argv) != 3 or argv[0] != "--build" or argv[2] not in ("pov", "cycles", "eevee"):
        print("usage: render_test.py --build BUILD pov|cycles|eevee", file=sys.stderr)
        return 2
    build, target = argv[1], argv[2]
    names = [n for n, kinds in compare.TEST_SCENES.items()
             if kinds.get(target) in ("exact", "approx")]
    opts = compare.parse(["--build", build, "--targets", target, "--set", "tests",
                          "--scenes", ",".join(names),
                          "--work", os.path.join(build, "scene_export", "compare")])
    results = compare.compare_all(opts)
    failed = [r["scene"] for r in results if r["pass"] is False]
    if len(results) != len(names):
        print("FAIL: %d scenes compared, %d expected" % (len(results), len(names)))
        return 1
    if failed:
        print("FAIL: outside the bound: %s" % ", ".join(failed))
        return 1
    print("all %d scenes within their bounds" % len(results))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
