"""What the exporters make of the non-uniform media (issue 12, part 4): the
figures of docs/scene_export.md, "Non-uniform media".

  python3 -m validation.export_media [--build-dir DIR] [--scenes a,b]
      [--parts pov,cycles,phase] [--ref-spp N] [--samples N] [--work DIR]
      [--markdown FILE]

For each scene (scene_export/testdata, small): the reference (lmm_tracer
--mode reference), then
- pov: the POV-Ray export as written (media method 2, jitter 0, 200
  intervals of one sample; an atmosphere with Mie in two frames, summed),
  with fewer intervals (50), and with
  POV-Ray's own default sampling (`method 3` and its defaults: the
  exporter's method, intervals, samples and jitter lines removed), which
  the semantics notes call biased;
- cycles: the Cycles export as written (its height-fog or atmosphere step
  rate) at two seeds (their difference is Cycles' noise), and with steps
  four times longer (the data's step_rate times 4) and, for an atmosphere,
  four times shorter;
- phase: the largest and RMS relative error over cos of the
  Henyey-Greenstein lobe of the Cornette-Shanks phase's mean cosine
  (se_phase_cs_mean_cosine), which both targets used before the fitted
  lobes (se_phase_fit.h; scene_export/se_phase_fit_test prints the fits'
  errors), for a few g.
Every image is compared with the reference by shafts_compare (mean_rel over
the lit pixels and the luminance ratio, the project's one definition of
error). Renders run under the caller's priority; nothing is cached.
"""

import argparse
import json
import math
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .metrics import compare
from .renderers import pov_frames

ROOT = Path(__file__).resolve().parent.parent
TESTDATA = ROOT / "scene_export" / "testdata"
SCENES = ["height_fog_spot", "height_fog_sun"]


def run(cmd, cwd=None, env=None):
    """Runs a command; returns its wall time in seconds. Raises on failure."""
    t = time.monotonic()
    proc = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, check=False)
    if proc.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (cmd[0], proc.returncode,
                                                   proc.stdout.decode(errors="replace")[-800:]))
    return time.monotonic() - t


def pov_variants():
    """(label, edit of the .pov text): the export as written and variations."""
    def intervals(n, k=1):
        def edit(text):
            text = re.sub(r"(?m)^(\s*intervals\s+)\d+", r"\g<1>%d" % n, text)
            return re.sub(r"(?m)^(\s*samples\s+)\d+\s*,\s*\d+", r"\g<1>%d, %d" % (k, k), text)
        return edit

    def method3(text):
        return re.sub(r"(?m)^\s*(method|intervals|samples|jitter)\b.*\n", "", text)

    return [("method 2, 50 intervals", intervals(50)),
            ("method 2, 200 intervals (export)", None),
            ("method 3, POV-Ray's defaults", method3)]


def pov_image(tools, scene, work, label, edit):
    d = work / ("pov_" + re.sub(r"[^a-z0-9]+", "_", label.lower()))
    d.mkdir()
    run([tools["scene_export"], scene, "--to", "pov", "-o", d / "scene.pov"])
    if edit:
        pov = d / "scene.pov"
        pov.write_text(edit(pov.read_text()))
    seconds = run(["povray", "scene.ini"], cwd=d, env={"HOME": str(d), "PATH": "/usr/bin:/bin"})
    return pov_frames(d), seconds


def cycles_image(tools, scene, work, label, samples, seed, step_factor):
    d = work / ("cycles_%s_%d" % (re.sub(r"[^a-z0-9]+", "_", label.lower()), seed))
    d.mkdir()
    run([tools["scene_export"], scene, "--to", "blender", "-o", d / "scene.py"])
    data = d / "scene.blender.json"
    j = json.loads(data.read_text())
    medium = j.get("medium", {})
    marched = medium.get("height_fog") or medium.get("atmosphere")
    if marched and step_factor != 1:
        marched["step_rate"] *= step_factor
        # The longest ray's steps (Blender holds at most 65536).
        marched["max_steps"] = min(65536, int(marched["max_steps"] / min(step_factor, 1.0)) + 1)
        data.write_text(json.dumps(j))
    seconds = run(["blender", "-b", "-P", d / "scene.py", "--", "--engine", "cycles",
                   "--out", d / "out.exr", "--samples", samples, "--seed", seed])
    return d / "out.exr", seconds


def phase_rows():
    """The Cornette-Shanks phase against its Henyey-Greenstein lobe."""
    def cs(g, c):
        return 3 / (8 * math.pi) * (1 - g * g) / (2 + g * g) * (1 + c * c) / (
            1 + g * g - 2 * g * c) ** 1.5

    def hg(g, c):
        return (1 - g * g) / (4 * math.pi) / (1 + g * g - 2 * g * c) ** 1.5

    rows = []
    for g in (0.3, 0.5, 0.7, 0.76, 0.8, 0.9):
        lobe = 3 * g * (4 + g * g) / (5 * (2 + g * g))
        errs = [abs(hg(lobe, c) / cs(g, c) - 1) for c in (-1 + 2 * i / 4000 for i in range(4001))]
        fwd = hg(lobe, 1.0) / cs(g, 1.0) - 1
        rows.append({"g": g, "lobe_g": lobe, "max_rel": max(errs),
                     "rms_rel": math.sqrt(sum(e * e for e in errs) / len(errs)),
                     "forward": fwd})
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(ROOT / "build"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--parts", default="pov,cycles,phase")
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--samples", type=int, default=128, help="Cycles samples per pixel")
    ap.add_argument("--work", help="keep the images here (default: a temporary directory)")
    ap.add_argument("--markdown")
    args = ap.parse_args(argv)
    build = Path(args.build_dir)
    tools = {"scene_export": build / "scene_export" / "scene_export",
             "lmm_tracer": build / "lmm_tracer" / "lmm_tracer",
             "compare": build / "validation" / "shafts_compare"}
    for name, path in tools.items():
        if not path.exists():
            print("export_media: %s is not built (%s)" % (name, path), file=sys.stderr)
            return 2
    parts = set(args.parts.split(","))
    lines = []
    tmp = None
    if args.work:
        root = Path(args.work)
        root.mkdir(parents=True, exist_ok=True)
    else:
        tmp = tempfile.mkdtemp(prefix="export_media.")
        root = Path(tmp)
    try:
        if parts & {"pov", "cycles"}:
            lines += ["| scene | renderer, setting | mean rel. diff. | ratio | s/render |",
                      "|---|---|---|---|---|"]
        for name in filter(None, args.scenes.split(",")):
            scene = TESTDATA / (name + ".json")
            work = root / name
            if work.exists():
                shutil.rmtree(work)
            work.mkdir(parents=True)
            ref = work / "ref.exr"
            sec = run([tools["lmm_tracer"], scene, "--mode", "reference", "--spp", args.ref_spp,
                       "--seed", 0, "-q", "-o", ref])
            print("%s: reference, %d spp, %.1f s" % (name, args.ref_spp, sec), flush=True)

            def row(label, img, seconds):
                m = compare(tools["compare"], ref, img)
                lines.append("| %s | %s | %.4f | %.4f | %.1f |" % (
                    name, label, m["mean_rel"], m["scale"], seconds))
                print(lines[-1], flush=True)
                return m

            if "pov" in parts:
                for label, edit in pov_variants():
                    img, seconds = pov_image(tools, scene, work, label, edit)
                    row("POV-Ray, " + label, img, seconds)
            if "cycles" in parts:
                steps = [("export's step rate", 1), ("steps 4x longer", 4)]
                if json.loads(scene.read_text()).get("medium", {}).get("type") == "atmosphere":
                    steps.append(("steps 4x shorter", 0.25))
                for label, factor in steps:
                    img, seconds = cycles_image(tools, scene, work, label, args.samples, 1, factor)
                    row("Cycles %d spp, %s" % (args.samples, label), img, seconds)
                    if factor == 1:
                        img2, _ = cycles_image(tools, scene, work, label, args.samples, 2, 1)
                        noise = compare(tools["compare"], img, img2)["mean_rel"]
                        lines.append("| %s | Cycles noise (seed 2 against seed 1) | %.4f | - | - |"
                                     % (name, noise))
                        print(lines[-1], flush=True)
        if "phase" in parts:
            lines += ["", "| Cornette-Shanks g | lobe g (mean cosine) | largest rel. error | "
                      "RMS rel. error | at cos = 1 |", "|---|---|---|---|---|"]
            for r in phase_rows():
                lines.append("| %.2f | %.4f | %.3f | %.3f | %+.3f |" % (
                    r["g"], r["lobe_g"], r["max_rel"], r["rms_rel"], r["forward"]))
            print("\n".join(lines[-8:]), flush=True)
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)
    if args.markdown:
        Path(args.markdown).write_text("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
