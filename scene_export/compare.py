#!/usr/bin/env python3
"""Agreement of POV-Ray, Cycles and EEVEE with the reference renderer.

For each scene: render the reference (lmm_tracer --mode reference, many
in-scattering samples), export the scene with scene_export, render it with
the target, and compare the two linear EXR images with se_imgdiff over the
lit region (pixels whose reference value exceeds 1% of the image's largest).
Cycles is rendered with two seeds: their difference, relative to the
reference, measures its noise.

  compare.py [--build DIR] [--targets pov,cycles,eevee] [--set tests|canonical|all]
             [--work DIR] [--markdown FILE] [--json FILE]

Python 3 standard library only; the image statistics come from se_imgdiff
(scene_export/imgdiff.c). The test render_test.py imports this module and
checks the bounds stated in BOUNDS below (docs/scene_export.md explains
them).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)

# The test scenes (scene_export/testdata) and what each target makes of
# them: "exact" scenes must agree within the bound, "approx" scenes use a
# feature the target approximates and are held to a looser regression bound.
TEST_SCENES = {
    "point_medium": {"pov": "exact", "cycles": "exact", "eevee": "report"},
    "spot_sphere": {"pov": "exact", "cycles": "exact", "eevee": "report"},
    "sun_window": {"pov": "exact", "cycles": "exact", "eevee": "report"},
    "spot_gobo": {"pov": "exact", "cycles": "exact", "eevee": "report"},
    "lambert_floor": {"pov": "exact", "cycles": "exact", "eevee": "exact"},
    "semi_shadow": {"pov": "exact", "cycles": "exact", "eevee": "report"},
    "phase_henyey_greenstein": {"pov": "exact", "cycles": "exact", "eevee": "report"},
    "phase_nishita_hazy": {"pov": "exact", "cycles": "approx", "eevee": "report"},
    "phase_nishita_murky": {"pov": "exact", "cycles": "approx", "eevee": "report"},
    "phase_rayleigh": {"pov": "exact", "cycles": "approx", "eevee": "report"},
    "everything": {"pov": "approx", "cycles": "approx", "eevee": "report"},
}

CANONICAL_SCENES = ["lmm_lens", "lmm_table", "lmm_table_glass", "mountains_sun",
                    "stage_5spots", "stained_glass", "teapot_spot"]

# Bounds on the mean relative difference over the lit region.
#  pov exact: POV-Ray is deterministic; its errors are the midpoint rule of
#    media method 2 (200 intervals in draft quality: about 1/200 of a shadow
#    edge's contrast where a ray crosses one), half-float output (2^-11),
#    the fade approximation of 1/r^2 ((f/r)^2 < 1e-8) and the reference's own
#    error at 1024 samples (< 0.1%, measured from two seeds): 1% holds all
#    with a margin, and the total (ratio) must agree within 0.5%.
#  cycles exact: Cycles is unbiased for these scenes, so its difference from
#    the reference is noise. Two seeds differ by about sqrt(2) times the
#    noise of one image, so the bound is that difference (measured on the
#    spot) plus 0.5% for the reference's error and tessellation, and the
#    total must agree within 1%.
#  approx: the measured error of the approximation plus a margin, so that
#    regressions show; docs/scene_export.md lists the numbers.
BOUNDS = {
    ("pov", "exact"): {"mean_rel": 0.01, "ratio": 0.005},
    ("pov", "approx"): {"mean_rel": 0.02, "ratio": 0.01},
    ("cycles", "exact"): {"mean_rel": "noise+0.005", "ratio": 0.01},
    ("cycles", "approx"): {"mean_rel": 0.35, "ratio": 0.4},
    ("eevee", "exact"): {"mean_rel": 0.02, "ratio": 0.02},
}


class Tools:
    def __init__(self, build):
        self.build = os.path.abspath(build)
        self.export = os.path.join(self.build, "scene_export", "scene_export")
        self.imgdiff = os.path.join(self.build, "scene_export", "se_imgdiff")
        self.tracer = os.path.join(self.build, "lmm_tracer", "lmm_tracer")
        for tool in (self.export, self.imgdiff, self.tracer):
            if not os.access(tool, os.X_OK):
                raise SystemExit("compare.py: %s is missing; build the project first" % tool)


def run(cmd, cwd=None, timeout=900):
    """Runs a command; returns its seconds, raising with its output on failure."""
    start = time.time()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError("%s failed (exit %d):\n%s" % (" ".join(cmd), p.returncode,
                                                         p.stdout.decode(errors="replace")[-3000:]))
    return time.time() - start


def imgdiff(tools, ref, test, mask=None):
    cmd = [tools.imgdiff, ref, test] + (["--mask", mask] if mask else [])
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, check=True)
    return json.loads(p.stdout)


def reference(tools, scene, work, spp):
    """The reference image, cached in work/ref (rendered again if the scene
    or the tracer is newer)."""
    name = os.path.splitext(os.path.basename(scene))[0]
    out = os.path.join(work, "ref", "%s.spp%d.exr" % (name, spp))
    os.makedirs(os.path.dirname(out), exist_ok=True)
    newest = max(os.path.getmtime(scene), os.path.getmtime(tools.tracer))
    if not os.path.exists(out) or os.path.getmtime(out) < newest:
        run([tools.tracer, scene, "-o", out, "--mode", "reference", "--spp", str(spp),
             "--quiet"])
    return out


def render_pov(tools, scene, work, quality):
    name = os.path.splitext(os.path.basename(scene))[0]
    d = os.path.join(work, "pov", name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    run([tools.export, scene, "--to", "pov", "-o", os.path.join(d, name + ".pov"),
         "--quality", quality])
    seconds = run(["povray", name + ".ini"], cwd=d)
    return os.path.join(d, name + ".exr"), seconds


def export_blender(tools, scene, work, quality, engine):
    name = os.path.splitext(os.path.basename(scene))[0]
    d = os.path.join(work, engine, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    script = os.path.join(d, name + ".py")
    run([tools.export, scene, "--to", "blender", "-o", script, "--quality", quality])
    return script


def render_blender(script, engine, samples, seed):
    d = os.path.dirname(script)
    out = os.path.join(d, "%s.seed%d.exr" % (engine, seed))
    cmd = ["blender", "-b", "-P", script, "--", "--engine", engine, "--out", out,
           "--samples", str(samples), "--seed", str(seed)]
    if engine == "eevee":
        cmd = ["xvfb-run", "-a", "-s", "-screen 0 640x480x24"] + cmd
    seconds = run(cmd, cwd=d)
    return out, seconds


def compare_scene(tools, scene, target, work, opts):
    ref = reference(tools, scene, work, opts.ref_spp)
    result = {"scene": os.path.splitext(os.path.basename(scene))[0], "target": target}
    if target == "pov":
        img, seconds = render_pov(tools, scene, work, opts.quality)
        result.update(imgdiff(tools, ref, img))
    else:
        script = export_blender(tools, scene, work, opts.quality, target)
        samples = opts.samples if target == "cycles" else opts.eevee_samples
        img, seconds = render_blender(script, target, samples, 0)
        result.update(imgdiff(tools, ref, img))
        result["samples"] = samples
        if target == "cycles":
            img1, s1 = render_blender(script, target, samples, 1)
            seconds = (seconds + s1) / 2
            result["noise"] = imgdiff(tools, img1, img, mask=ref)["mean_rel"]
    result["seconds"] = round(seconds, 2)
    return result


def bound_for(target, kind, result):
    b = BOUNDS.get((target, kind))
    if not b:
        return None
    mean = b["mean_rel"]
    if isinstance(mean, str):  # "noise+X"
        mean = result.get("noise", 0.0) + float(mean.split("+")[1])
    return {"mean_rel": mean, "ratio": b["ratio"]}


def check(result, bound):
    if bound is None:
        return None
    return (result["mean_rel"] <= bound["mean_rel"]
            and abs(result["ratio"] - 1.0) <= bound["ratio"])


def canonical_copy(name, work, width=80, height=60):
    """A canonical scene at a small size, its file names made absolute."""
    src = os.path.join(SOURCE, "scenes", name + ".json")
    with open(src) as f:
        scene = json.load(f)
    scene["camera"]["width"], scene["camera"]["height"] = width, height

    def fix(o):
        if isinstance(o, dict):
            for k, v in o.items():
                if k in ("image", "file") and isinstance(v, str) and not os.path.isabs(v):
                    o[k] = os.path.join(SOURCE, "scenes", v)
                else:
                    fix(v)
        elif isinstance(o, list):
            for v in o:
                fix(v)
    fix(scene)
    d = os.path.join(work, "canonical")
    os.makedirs(d, exist_ok=True)
    out = os.path.join(d, name + ".json")
    text = json.dumps(scene, indent=1)
    if not os.path.exists(out) or open(out).read() != text:
        with open(out, "w") as f:
            f.write(text)
    return out


def scenes_for(which, work):
    """(path, {target: kind}) pairs."""
    items = []
    if which in ("tests", "all"):
        for name, kinds in TEST_SCENES.items():
            items.append((os.path.join(HERE, "testdata", name + ".json"), kinds))
    if which in ("canonical", "all"):
        for name in CANONICAL_SCENES:
            items.append((canonical_copy(name, work),
                          {"pov": "report", "cycles": "report", "eevee": "report"}))
    return items


def markdown(results):
    lines = ["| scene | target | mean rel. diff. | ratio | p90 | Cycles noise (2 seeds) | bound | pass | s/render |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        b = r.get("bound")
        lines.append("| %s | %s | %.4f | %.4f | %.4f | %s | %s | %s | %.1f |" % (
            r["scene"], r["target"] + ("" if r["kind"] in ("exact", "report") else " (approx.)"),
            r["mean_rel"], r["ratio"], r["p90_rel"],
            "%.4f" % r["noise"] if "noise" in r else "-",
            "%.4f" % b["mean_rel"] if b else "-",
            {True: "yes", False: "NO", None: "-"}[r.get("pass")], r["seconds"]))
    return "\n".join(lines) + "\n"


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(SOURCE, "build"))
    ap.add_argument("--targets", default="pov,cycles")
    ap.add_argument("--set", default="tests", choices=("tests", "canonical", "all"))
    ap.add_argument("--scenes", default="", help="comma-separated scene names to keep")
    ap.add_argument("--work", default=None, help="work directory (default: BUILD/scene_export/compare)")
    ap.add_argument("--quality", default="draft", choices=("draft", "final"))
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--samples", type=int, default=128, help="Cycles samples per pixel")
    ap.add_argument("--eevee-samples", type=int, default=16)
    ap.add_argument("--markdown", default=None)
    ap.add_argument("--json", default=None)
    return ap.parse_args(argv)


def compare_all(opts, report=print):
    tools = Tools(opts.build)
    work = opts.work or os.path.join(tools.build, "scene_export", "compare")
    os.makedirs(work, exist_ok=True)
    keep = set(filter(None, opts.scenes.split(",")))
    results = []
    for target in opts.targets.split(","):
        for scene, kinds in scenes_for(opts.set, work):
            name = os.path.splitext(os.path.basename(scene))[0]
            if keep and name not in keep:
                continue
            kind = kinds.get(target, "report")
            r = compare_scene(tools, scene, target, work, opts)
            r["kind"] = kind
            r["bound"] = bound_for(target, kind, r)
            r["pass"] = check(r, r["bound"])
            results.append(r)
            report("%-26s %-7s mean_rel %.4f ratio %.4f%s  bound %s  %s" % (
                name, target, r["mean_rel"], r["ratio"],
                "  noise %.4f" % r["noise"] if "noise" in r else "",
                "%.4f" % r["bound"]["mean_rel"] if r["bound"] else "-",
                {True: "ok", False: "FAIL", None: "(reported)"}[r["pass"]]))
            sys.stdout.flush()
    return results


def main(argv):
    opts = parse(argv)
    results = compare_all(opts)
    if opts.markdown:
        with open(opts.markdown, "w") as f:
            f.write(markdown(results))
    if opts.json:
        with open(opts.json, "w") as f:
            json.dump(results, f, indent=1)
    return 1 if any(r["pass"] is False for r in results) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
