"""The hard cases: a stability suite for every renderer (the runner; the
cases are in cases.py, their bounds in bounds.py).

Scenes generated here push a renderer where single scattering is hard: a
point light on the camera ray (the 1/r^2 singularity), a light exactly on a
virtual plane of the sweep, the camera inside a spot cone looking up it, a
very dense and a very thin medium, 2000 planes, all lengths scaled by 1e-3
and by 1e4, the murky phase function's forward peak, a directional light
grazing the planes, a hard-edged spot, a light behind the camera, and a 1x1
image. Every available renderer renders each of them (at the setting a user
would use, plus the case's own), and each rendering is checked for

  * stability: no NaN, no infinity, no negative radiance (everywhere, the
    singular pixels included);
  * accuracy: relative RMS error over the lit region against the converged
    reference within the bound stated in bounds.py for that renderer (pixels on
    and next to a light seen by the camera, where the true radiance is
    unbounded, are masked out of this check only);
  * invariances: a scaled scene gives its base scene's image, a 1x1 image
    is the centre pixel of a 3x3 one, a light on a plane boundary and one on
    a slab's sample depth agree.

Run alone (the quick form is a CTest test), from the source tree:

  python3 -m validation.hard --build-dir build [--quick|--full] [--renderers a,b]
                [--cache DIR] [--json OUT.json]

Exit status 0 if every check of every available renderer passed, 1 if one
failed, 2 for bad arguments or a missing reference renderer.
"""

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from .. import renderers
from ..metrics import CompareFailed, compare, fmt_percent, mask_image
from ..progress import ProgressExecutor
from ..runs import LocalExecutor, RunCache, plan_run
from ..scenes import light_mask, prepare_data
from .bounds import (BLACK_BOUNDS, INVARIANCE_BOUNDS, black_bound, bound_for,
                     bounds_table, known_issue)
from .cases import CASES
from .inputs import run_inputs

# Relative file names in a case's scene resolve here.
VALIDATION = Path(__file__).resolve().parent.parent

# ---------------------------------------------------------------------------
# Running and checking.

def case_size(case, mode):
    """The image size a case renders at: small, odd for centred lights."""
    w, h = (64, 48) if mode == "quick" else (160, 120)
    if case.odd:
        w, h = w + 1, h + 1
    return w, h


def _centre_pixel(src, dst):
    """The centre pixel of a 3x3 image as a 1x1 image (oiiotool)."""
    subprocess.run(["oiiotool", str(src), "--cut", "1x1+1+1", "-d", "float", "-o", str(dst)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return dst


def reference_spp(mode):
    """The ground truth's samples: converged to well below every bound."""
    return 1024 if mode == "quick" else 4096


def _case_scenes(case, mode, cache):
    """A case's scene data, its prepared scene, and the prepared scene of
    its ground truth (another case's for the scaled ones)."""
    w, h = case_size(case, mode)
    data = case.build(w, h)
    prepared = prepare_data("hard-" + case.name, data, VALIDATION, cache.root)
    truth = prepared
    if case.reference_case:
        other = next(c for c in CASES if c.name == case.reference_case)
        truth = prepare_data("hard-" + other.name, other.build(w, h), VALIDATION, cache.root)
    return data, prepared, truth


def _case_settings(ctx, case, adapter, prepared):
    """The (kind, label, params) an adapter renders a case with: [] if the
    case is not for it, a string (the reason) if the image is too small."""
    if case.only and adapter.name not in case.only:
        return []
    if min(prepared.width, prepared.height) < adapter.min_image_side:
        return adapter.min_image_why
    if adapter.name in case.extra:
        return [("case", label, dict(adapter.hard_case_settings(ctx)[0][2], **p))
                for label, p in case.extra[adapter.name]]
    return adapter.hard_case_settings(ctx)


def reference_params(mode):
    return {"mode": "reference", "spp": reference_spp(mode), "seed": 0}


def planned_runs(ctx, adapters, cache):
    """Every run of the suite (runs.Run), for an executor that renders
    them all ahead of the checks."""
    out = []
    for case in CASES:
        _, prepared, truth = _case_scenes(case, ctx.mode, cache)
        out.append(plan_run(ctx, renderers.REFERENCE, truth, reference_params(ctx.mode),
                            "reference"))
        for adapter in adapters:
            settings = _case_settings(ctx, case, adapter, prepared)
            if isinstance(settings, list):
                out += [plan_run(ctx, adapter, prepared, params, label)
                        for _, label, params in settings]
    return out


def run_suite(ctx, adapters, cache, scratch, say=print, retry_failed=False,
              image_dir=None, executor=None):
    """Renders and checks every case with every available adapter. Returns
    a dict: the cases (name, description, size, bounds) and per case and
    renderer the renderings with their checks. Images (previews and
    difference PNGs) go to image_dir when it is given. Runs are rendered by
    `executor` (default: here, runs.LocalExecutor)."""
    executor = executor or LocalExecutor(ctx, cache, retry_failed)
    scratch = Path(scratch)
    ref_adapter = renderers.REFERENCE
    compare_tool = ctx.tool("validation/shafts_compare")
    results = {"mode": ctx.mode, "reference_spp": reference_spp(ctx.mode), "cases": [],
               "renderers": [a.name for a in adapters],
               "bounds": bounds_table(ctx.mode, [a.name for a in adapters])}
    images = {}  # (case, renderer, label) -> EXR path, for invariances
    for case in CASES:
        data, prepared, truth = _case_scenes(case, ctx.mode, cache)
        mask = light_mask(data) if case.mask_lights else []
        entry = {"name": case.name, "description": case.description,
                 "width": prepared.width, "height": prepared.height,
                 "masked_pixels": sum(r[2] * r[3] for r in mask), "renderings": []}
        results["cases"].append(entry)
        if case.reference_case:
            entry["reference_case"] = case.reference_case
        ref = executor.run(plan_run(ctx, ref_adapter, truth, reference_params(ctx.mode),
                                    "reference"), say=say)
        entry["reference"] = {"status": ref["status"], "error": ref.get("error"),
                              "seconds": ref.get("tool_seconds"),
                              "wall_seconds": ref.get("wall_seconds")}
        if ref["status"] != "ok":
            entry["error"] = "the reference failed: %s" % ref.get("error")
            continue
        ref_img = mask_image(ref["image"], mask, scratch / ("%s-ref.exr" % case.name))
        if image_dir:
            d = Path(image_dir) / case.name
            d.mkdir(parents=True, exist_ok=True)
            compare(compare_tool, ref["image"], ref["image"], preview=d / "reference.png")
            entry["reference"]["png"] = str(d / "reference.png")
        for adapter in adapters:
            settings = _case_settings(ctx, case, adapter, prepared)
            if isinstance(settings, str):
                entry.setdefault("skipped", []).append(
                    {"renderer": adapter.name, "why": settings})
                continue
            for kind, label, params in settings:
                run = executor.run(plan_run(ctx, adapter, prepared, params, label), say=say)
                r = {"renderer": adapter.name, "label": label, "kind": kind,
                     "status": run["status"], "error": run.get("error"),
                     "seconds": run.get("tool_seconds"),
                     "wall_seconds": run.get("wall_seconds"), "checks": []}
                entry["renderings"].append(r)
                if run["status"] != "ok":
                    r["checks"].append({"name": "renders", "ok": False, "note": run.get("error")})
                    continue
                images[(case.name, adapter.name, label)] = run["image"]
                _check(ctx, case, adapter, r, run, ref_img, mask, scratch, compare_tool,
                       image_dir)
        # Invariances need both images of the same renderer.
        for kind, other in case.invariance:
            for r in entry["renderings"]:
                if r["status"] != "ok":
                    continue
                _check_invariance(case, kind, other, r, entry, images, scratch, compare_tool)
        for r in entry["renderings"]:
            for chk in r["checks"]:
                note = known_issue(r["renderer"], case.name, chk["name"])
                if note:
                    chk["known"] = note
                    if not chk["ok"]:
                        chk["ok"] = True
                        chk["known_failure"] = True
            r["ok"] = all(c["ok"] for c in r["checks"])
    # Bad input and files (issue 11, kinds 5 to 8): refused as they must be.
    results["cases"] += run_inputs(ctx, adapters, scratch)
    results["failures"] = failures(results)
    results["known_failures"] = [(c["name"], r["renderer"], r["label"], k["name"], k["known"])
                                 for c in results["cases"] for r in c["renderings"]
                                 for k in r["checks"] if k.get("known_failure")]
    return results


def _check(ctx, case, adapter, r, run, ref_img, mask, scratch, tool, image_dir):
    """Stability on the whole image, accuracy on the unmasked pixels."""
    tag = "%s-%s-%s" % (case.name, adapter.name, _slug(r["label"]))
    try:
        whole = compare(tool, ref_img, run["image"])
        img = mask_image(run["image"], mask, scratch / (tag + ".exr"))
        png = diff = None
        if image_dir:
            d = Path(image_dir) / case.name
            png, diff = d / ("%s-%s.png" % (adapter.name, _slug(r["label"]))), \
                d / ("%s-%s.diff.png" % (adapter.name, _slug(r["label"])))
        m = compare(tool, ref_img, img, diff=diff, preview=png)
    except (CompareFailed, subprocess.CalledProcessError) as e:
        r["checks"].append({"name": "compares", "ok": False, "note": str(e)})
        return
    if png:
        r["png"], r["diff_png"] = str(png), str(diff)
    r["metrics"] = m
    r["checks"].append({"name": "finite, non-negative", "ok": whole["bad_values"] == 0,
                        "value": whole["bad_values"], "bound": 0})
    bound = bound_for(adapter.name, r["kind"], case.name, ctx.mode)
    if case.black:
        # The truth is 0 everywhere (its lit region is empty, so the error
        # says nothing): the largest value must be 0 too, where the
        # renderer's error is bounded (or at most its stated BLACK_BOUNDS).
        black = black_bound(adapter.name, case.name)
        note = BLACK_BOUNDS.get((adapter.name, case.name), (0, None))[1]
        r["checks"].append({"name": "black (largest value)",
                            "ok": bound is None or whole["max_abs"] <= black,
                            "value": whole["max_abs"], "bound": black if bound is not None else None,
                            "note": note if bound is not None else "reported, not bounded"})
    r["checks"].append({"name": "error", "ok": bound is None or m["rel_rms"] <= bound,
                        "value": m["rel_rms"], "bound": bound,
                        "note": None if bound is not None else "reported, not bounded"})


def _check_invariance(case, kind, other, r, entry, images, scratch, tool):
    """Compares a rendering with the one it should equal."""
    bound = INVARIANCE_BOUNDS.get(r["renderer"], {}).get(kind)
    mine = images.get((case.name, r["renderer"], r["label"]))
    if kind == "plane":
        # The renderer's first setting of the same case: the check goes on
        # every later one.
        same = [x for x in entry["renderings"] if x["renderer"] == r["renderer"]]
        if len(same) < 2 or same[0] is r:
            return
        theirs = images.get((case.name, r["renderer"], same[0]["label"]))
        if theirs is None:
            return
        name = "equals %s" % same[0]["label"]
    else:
        theirs = images.get((other, r["renderer"], r["label"]))
        if theirs is None:
            return
        name = "equals %s" % other
        if kind == "pixel":
            theirs = _centre_pixel(theirs, scratch / ("%s-%s-centre.exr" % (other, r["renderer"])))
            name = "equals the centre pixel of %s" % other
    try:
        m = compare(tool, theirs, mine, lit=0.0)
    except (CompareFailed, subprocess.CalledProcessError) as e:
        r["checks"].append({"name": name, "ok": False, "note": str(e)})
        return
    r["checks"].append({"name": name, "ok": bound is None or m["rel_rms"] <= bound,
                        "value": m["rel_rms"], "bound": bound,
                        "note": None if bound is not None else "reported, not bounded"})


def _slug(text):
    return "".join(c if c.isalnum() else "-" for c in text).strip("-").lower() or "run"


def failures(results):
    """The failed checks as (case, renderer, label, check name, detail)."""
    out = []
    for c in results["cases"]:
        if c.get("error"):
            out.append((c["name"], "reference", "", "renders", c["error"]))
        for r in c["renderings"]:
            for chk in r["checks"]:
                if not chk["ok"]:
                    detail = chk.get("note") or _check_detail(chk)
                    out.append((c["name"], r["renderer"], r["label"], chk["name"], detail))
    return out


def _check_detail(chk):
    """A failed check's value against its bound, for people."""
    if chk["name"] == "finite, non-negative":
        return "%d bad values" % (chk.get("value") or 0)
    return "%s (bound %s)" % (fmt_percent(chk.get("value") or 0), fmt_percent(chk.get("bound")))


def print_table(results, out=sys.stdout):
    """A plain-text table of every rendering and its checks."""
    for c in results["cases"]:
        if c.get("error"):
            print("%-22s %s" % (c["name"], c["error"]), file=out)
        for r in c["renderings"]:
            m = r.get("metrics") or {}
            err = m.get("rel_rms")
            if r.get("kind") == "input":
                print("%-22s %-11s %-18s %-4s %s" % (c["name"], r["renderer"], r["label"][:18],
                                                      "ok" if r.get("ok") else "FAIL",
                                                      r["checks"][0]["note"][:100]), file=out)
                continue
            bound = next((k.get("bound") for k in r["checks"] if k["name"] == "error"), None)
            inv = [k for k in r["checks"] if k["name"].startswith("equals")]
            print("%-22s %-11s %-18s %-4s error %-9s bound %-6s %s" % (
                c["name"], r["renderer"], r["label"][:18], "ok" if r.get("ok") else "FAIL",
                fmt_percent(err) if err is not None else "-",
                fmt_percent(bound) if bound is not None else "-",
                "; ".join("%s %s%s" % (k["name"], fmt_percent(k.get("value") or 0),
                                          " KNOWN FAILURE" if k.get("known_failure") else
                                          "" if k["ok"] else " FAIL") for k in inv)),
                file=out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", dest="mode", action="store_const", const="quick")
    g.add_argument("--full", dest="mode", action="store_const", const="full")
    ap.add_argument("--build-dir", default=str(VALIDATION.parent / "build"))
    ap.add_argument("--renderers", default="lmm_tracer,gl_shafts",
                    help="comma-separated adapters (default: lmm_tracer,gl_shafts)")
    ap.add_argument("--cache", help="run cache (default: a temporary directory)")
    ap.add_argument("--json", help="write the results as JSON")
    ap.add_argument("--images", help="write previews and difference images here")
    ap.add_argument("--retry-failed", action="store_true")
    args = ap.parse_args(argv)
    mode = args.mode or "quick"
    ctx = renderers.Context(VALIDATION.parent, args.build_dir, mode=mode, say=lambda m: None)
    try:
        wanted = renderers.by_name(args.renderers)
    except ValueError as e:
        print("hard_cases: %s" % e, file=sys.stderr)
        return 2
    if renderers.REFERENCE.missing(ctx) or not ctx.tool("validation/shafts_compare").exists():
        print("hard_cases: lmm_tracer and shafts_compare must be built in %s" % ctx.build,
              file=sys.stderr)
        return 2
    if not shutil.which("oiiotool"):
        print("hard_cases: oiiotool is missing (Debian's openimageio-tools)", file=sys.stderr)
        return 2
    adapters = []
    for a in wanted:
        note = a.missing(ctx)
        if note:
            print("hard_cases: skipping %s: %s" % (a.name, note))
        else:
            adapters.append(a)
    with tempfile.TemporaryDirectory(prefix="hard_cases.") as tmp:
        cache = RunCache(args.cache or Path(tmp) / "cache")
        scratch = Path(tmp) / "scratch"
        scratch.mkdir()
        executor = ProgressExecutor(LocalExecutor(ctx, cache, args.retry_failed), cache,
                                    planned_runs(ctx, adapters, cache), args.retry_failed)
        results = run_suite(ctx, adapters, cache, scratch, say=lambda m: print(m, flush=True),
                            image_dir=args.images, executor=executor)
    print_table(results)
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=1) + "\n")
    bad = failures(results)
    for f in bad:
        print("FAIL: %s / %s %s: %s: %s" % f)
    for f in results["known_failures"]:
        print("known failure: %s / %s %s: %s: %s" % f)
    print("hard cases: %d renderings, %d failed checks" % (
        sum(len(c["renderings"]) for c in results["cases"]), len(bad)))
    return 1 if bad else 0
