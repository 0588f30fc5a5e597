"""Cross-renderer validation: every scene, every renderer, against the
converged reference, in error and in time.

  python3 -m validation.validate [--quick | --full] --report DIR [--scenes DIR_OR_FILE ...]
              [--cache DIR] [--build-dir DIR] [--renderers a,b,...]
              [--scale F] [--ref-spp N] [--no-hard-cases] [--no-twins]
              [--retry-failed] [--executor local|slurm] [--partition P] [--account A] ...

For each scene: the converged reference (lmm_tracer --mode reference at
high spp), then each renderer's sweep (renderers.py: gl_shafts over planes,
lattice and --xi; lmm_tracer over spp and modes; POV-Ray over media
intervals; Cycles over samples; EEVEE over volumetric settings), each run
timed and compared with the reference (shafts_compare); after a scene, its
twin (twins.py: the phase and highlights every peer represents exactly),
and every renderer's verdict on both: bias or noise (verdicts.py). Then the hard-case
stability suite (validation/hard/). Writes DIR/index.html, DIR/summary.md and
DIR/results.json; runs are cached (runs.py) so a re-run renders only what
changed and an interrupted run resumes. A renderer that is missing or fails
is skipped with a note in the report. With --executor slurm every run the
cache lacks is rendered first, as tasks of Slurm job arrays (slurm.py), and
the comparisons then read them from the cache: the same results.

Exit status: 0 when the report is written (renderer failures are in it;
with --strict, 1 if a hard case failed), 1 if the reference itself failed
for a scene or a hard case (the report then measures nothing there) or a
Slurm task failed for good (its run is reported failed and not cached: run
again to resume), 2 for bad arguments, a missing build, or a Slurm that
cannot render the sweep (no sbatch, nodes that do not see the cache).
"""

import argparse
import json
import os
import platform
import re
import shutil
import sys
import tempfile
import time
from pathlib import Path

import subprocess

from . import renderers, report, slurm, verdicts
from .hard import runner as hard_cases
from .progress import ProgressExecutor
from .metrics import (CompareFailed, compare, fmt_percent, fmt_seconds, mask_image,
                      time_to_reach)
from .runs import LocalExecutor, RunCache, plan_run
from .scenes import find_scenes, light_mask, mode_scale, prepare_file, write_atomic
from .svgplot import speed_error_svg
from .twins import make_twin, prepare_twin

HERE = Path(__file__).resolve().parent

MODES = {
    # Image scale, reference spp, and the renderers of the hard cases.
    # warm_frames: gl_shafts' warm frame is the median of that many
    # in-process frames (gl_shafts_bench) after each command-line run.
    "quick": {"scale": 0.5, "ref_spp": 512, "hard": "lmm_tracer,gl_shafts", "warm_frames": 3},
    "full": {"scale": 1.0, "ref_spp": 4096, "hard": "", "warm_frames": 2},
}
LIT = 0.01
# The renderers a twin (twins.py) is rendered with: the peers it is made
# for, and the project's renderers for their speed beside them. POV-Ray
# represents the canonical scenes exactly (docs/scene_export.md), so its
# twin runs would repeat its scene's.
TWIN_RENDERERS = ("lmm_tracer", "gl_shafts", "cycles", "eevee", "addon_sweep", "addon_tracer")


def slug(text):
    """A file-name-safe form of a label."""
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "run"


def machine():
    """What the timings were measured on."""
    cpu = platform.processor() or "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cpu": cpu, "threads": os.cpu_count() or 0, "system": platform.platform()}


class Validation:
    """One validation run: its context, cache, report directory, tallies."""

    def __init__(self, ctx, cache, report_dir, adapters, ref_spp, executor, say, twins=True):
        self.ctx, self.cache, self.dir = ctx, cache, Path(report_dir)
        self.twins = twins
        self.adapters, self.ref_spp = adapters, ref_spp
        self.executor, self.say = executor, say
        self.compare_tool = ctx.tool("validation/shafts_compare")
        self.labels = {a.name: {"label": a.label} for a in adapters}
        self.rendered = self.cached = 0

    def run(self, adapter, scene, params, label):
        """One run, from the cache or rendered (by the executor)."""
        result = self.executor.run(plan_run(self.ctx, adapter, scene, params, label),
                                   say=lambda m: self.say("  " + m))
        if result.get("cached"):
            self.cached += 1
        else:
            self.rendered += 1
            if result["status"] != "ok":
                self.say("  %s: %s %s %s: %s" % (
                    scene.name, adapter.name, label,
                    "not exported" if result["status"] == "not_exported" else "failed",
                    result.get("error")))
        return result

    def reference_params(self):
        return {"mode": "reference", "spp": self.ref_spp, "seed": 0}, \
            "lmm_tracer reference, spp %d" % self.ref_spp

    def planned(self, path, scale):
        """Every run of one scene (the reference first), for an executor
        that renders a sweep ahead of its comparisons; [] if the scene
        cannot be read (scene() reports that)."""
        try:
            scene = prepare_file(path, self.cache.root, scale)
        except (OSError, ValueError):
            return []
        params, label = self.reference_params()
        out = [plan_run(self.ctx, renderers.REFERENCE, scene, params, label)]
        for adapter in self.adapters:
            out += [plan_run(self.ctx, adapter, scene, p, lab)
                    for lab, p in adapter.settings(self.ctx, scene)]
        twin = prepare_twin(path, self.cache.root, scale) if self.twins else None
        if twin:
            out.append(plan_run(self.ctx, renderers.REFERENCE, twin[0], params, label))
            for adapter in self.adapters:
                if adapter.name in TWIN_RENDERERS:
                    out += [plan_run(self.ctx, adapter, twin[0], p, lab)
                            for lab, p in adapter.settings(self.ctx, twin[0])]
        return out

    def scene(self, path, scale):
        """Renders and compares one scene; returns its entry of the results."""
        try:
            scene = prepare_file(path, self.cache.root, scale)
        except (OSError, ValueError) as e:
            name = Path(path).stem
            return {"name": name, "source": str(path), "error": "cannot read the scene: %s" % e}
        return self.measure(scene, self.adapters)

    def twin(self, path, scale, original):
        """Renders and compares the twin of a scene (twins.py) with the
        renderers of TWIN_RENDERERS; returns its entry, or None when the
        scene has no twin. Adds to `original` the twin's name and how far
        the twin's reference is from the scene's."""
        prepared = prepare_twin(path, self.cache.root, scale)
        if prepared is None or original.get("error"):
            return None
        scene, changes, data = prepared
        entry = self.measure(scene, [a for a in self.adapters if a.name in TWIN_RENDERERS])
        entry["twin_of"], entry["changes"] = original["name"], changes
        original["twin"] = {"name": scene.name, "changes": changes}
        if not entry.get("error"):
            try:
                original["twin"]["shift"] = compare(
                    self.compare_tool, original["reference"]["image"],
                    entry["reference"]["image"], lit=LIT)["rel_rms"]
            except CompareFailed:
                pass
            original["verdicts"] = verdicts.classify(original, data, twin=entry,
                                                     ref_spp=self.ref_spp)
        return entry

    def measure(self, scene, adapters):
        """Renders a prepared scene with `adapters` and compares every run
        with its reference; returns the scene's entry of the results."""
        self.say("%s (%dx%d)" % (scene.name, scene.width, scene.height))
        sdir = self.dir / "scenes" / scene.name
        sdir.mkdir(parents=True, exist_ok=True)
        entry = {"name": scene.name, "source": scene.source, "width": scene.width,
                 "height": scene.height, "has_medium": scene.has_medium, "runs": []}
        ref_params, ref_label = self.reference_params()
        ref = self.run(renderers.REFERENCE, scene, ref_params, ref_label)
        if ref["status"] != "ok":
            entry["error"] = "the reference failed: %s" % ref.get("error")
            return entry
        png = sdir / "reference.png"
        try:
            compare(self.compare_tool, ref["image"], ref["image"], preview=png,
                    exposure=scene.exposure)
        except CompareFailed as e:
            entry["error"] = "cannot read the reference image: %s" % e
            return entry
        entry["reference"] = {"label": ref_label, "tool_seconds": ref.get("tool_seconds"),
                              "wall_seconds": ref.get("wall_seconds"), "png": str(png),
                              "image": str(ref["image"])}
        # Lights in view: the errors are also measured without the pixels
        # next to them (scenes.light_mask), where radiance is unbounded.
        mask = light_mask(scene.data)
        masked_ref = None
        if mask:
            entry["masked_pixels"] = sum(r[2] * r[3] for r in mask)
            masked_ref = mask_image(ref["image"], mask, sdir / ".reference.masked.exr")
        for adapter in adapters:
            for label, params in adapter.settings(self.ctx, scene):
                result = self.run(adapter, scene, params, label)
                row = {"renderer": adapter.name, "label": label, "params": params,
                       "status": result["status"], "error": result.get("error"),
                       "tool_seconds": result.get("tool_seconds"),
                       "wall_seconds": result.get("wall_seconds"),
                       "warm_seconds": result.get("warm_seconds"),
                       "cached": result.get("cached", False)}
                entry["runs"].append(row)
                if result["status"] != "ok":
                    continue
                stem = "%s-%s" % (adapter.name, slug(label))
                try:
                    row["metrics"] = compare(self.compare_tool, ref["image"], result["image"],
                                             lit=LIT, diff=sdir / (stem + ".diff.png"),
                                             preview=sdir / (stem + ".png"),
                                             exposure=scene.exposure)
                    row["png"] = str(sdir / (stem + ".png"))
                    row["diff_png"] = str(sdir / (stem + ".diff.png"))
                    if masked_ref:
                        tmp = sdir / ".masked.exr"
                        row["metrics_masked"] = compare(
                            self.compare_tool, masked_ref,
                            mask_image(result["image"], mask, tmp), lit=LIT)
                        tmp.unlink()
                except (CompareFailed, subprocess.CalledProcessError) as e:
                    row["status"] = "failed"
                    row["compare_error"] = "cannot compare: %s" % e
        if masked_ref:
            Path(masked_ref).unlink()
        self._summarise(entry, "metrics", "time_to", "plot", "")
        if masked_ref:
            self._summarise(entry, "metrics_masked", "time_to_masked", "plot_masked",
                            ", away from the lights in view")
        self._self_check(entry)
        entry["verdicts"] = verdicts.classify(entry, scene.data, ref_spp=self.ref_spp)
        return entry

    def _summarise(self, entry, metrics, time_key, plot_key, what):
        """Each renderer's time to reach each error level, and the plot,
        from the runs' `metrics` figures."""
        series, entry[time_key] = [], {}
        for adapter in self.adapters:
            runs = [r for r in entry["runs"] if r["renderer"] == adapter.name]
            if runs and all(r["status"] == "not_exported" for r in runs):
                # The exporter refuses the scene for this renderer: no
                # curve, a row saying why (report.py).
                entry.setdefault("not_exported", {})[adapter.name] = runs[0].get("error")
                continue
            if not runs:
                continue
            # A renderer timed both ways (gl_shafts) is two series: its warm
            # in-process frame, the interactive comparison, and its first
            # image from the command line.
            ways = [(adapter.name, report._time_of, False)]
            if any(r.get("warm_seconds") is not None for r in runs):
                ways = [(adapter.name + report.WARM, lambda r: r.get("warm_seconds"), False),
                        (adapter.name, report._time_of, True)]
            for key, time_of, dashed in ways:
                pts = [(time_of(r), r[metrics]["rel_rms"], r["label"])
                       for r in runs if r.get(metrics)]
                tt = {"%g" % th: time_to_reach(pts, th) for th in report.THRESHOLDS}
                valid = [p for p in pts if p[0] is not None]
                if valid:
                    best = min(valid, key=lambda p: (p[1], p[0]))
                    tt["best"] = [best[1], best[0]]
                entry[time_key][key] = tt
                series.append({"label": report.series_label(self.labels, key, [w[0] for w in ways]),
                               "colour": adapter.colour, "dashed": dashed, "points": pts})
        plot = self.dir / "plots" / ("%s%s.svg" % (entry["name"], "-masked" if what else ""))
        write_atomic(plot, speed_error_svg(series, "%s: speed against error%s"
                                           % (entry["name"], what)))
        entry[plot_key] = str(plot)

    @staticmethod
    def _self_check(entry):
        """The reference's self-check: its error estimate is the error of
        the lmm_tracer reference run with the most samples below it."""
        checks = [r for r in entry["runs"] if r["renderer"] == renderers.REFERENCE.name
                  and r["params"].get("mode") == "reference" and r.get("metrics")]
        if checks and entry["has_medium"]:
            top = max(checks, key=lambda r: r["params"]["spp"])
            m = top.get("metrics_masked") or top["metrics"]
            entry["self_check"] = m["rel_rms"]
            entry["self_check_spp"] = top["params"]["spp"]


def command_line(argv):
    """The validation's command line as a user would type it."""
    args = sys.argv[1:] if argv is None else list(argv)
    return " ".join(["python3 -m validation.validate"] + [
        a if re.fullmatch(r"[\w./,=:+-]+", a) else "'%s'" % a.replace("'", "'\\''")
        for a in args])


def source_commit(root):
    """The source tree's commit (git describe --always --dirty), or None."""
    try:
        out = subprocess.run(["git", "-C", str(root), "describe", "--always", "--dirty"],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, timeout=30,
                             check=False)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return out.stdout.decode().strip() or None


def render_seconds(results):
    """The wall time of every run of the report, rendered now or cached:
    what the validation costs from an empty cache, comparisons aside."""
    total = 0.0
    for s in results["scenes"]:
        total += (s.get("reference") or {}).get("wall_seconds") or 0.0
        total += sum(r.get("wall_seconds") or 0.0 for r in s.get("runs", []))
    hc = results.get("hard_cases") or {}
    for c in hc.get("cases", []):
        total += (c.get("reference") or {}).get("wall_seconds") or 0.0
        total += sum(r.get("wall_seconds") or 0.0 for r in c.get("renderings", []))
    return total


def parse_args(argv):
    ap = argparse.ArgumentParser(
        description="Cross-renderer validation against the converged reference "
                    "(docs/validation.md).")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--quick", dest="mode", action="store_const", const="quick",
                   help="reduced image sizes and few settings: minutes (default)")
    g.add_argument("--full", dest="mode", action="store_const", const="full",
                   help="the scenes' own sizes and full sweeps")
    ap.add_argument("--report", required=True, help="the report directory")
    ap.add_argument("--scenes", nargs="+", metavar="DIR_OR_FILE",
                    help="scene files, or directories of them (default: scenes/)")
    ap.add_argument("--cache", "--cache-dir", dest="cache",
                    help="the run cache (default: BUILD/validation-cache); with "
                         "--executor slurm a directory every node sees at the same path")
    ap.add_argument("--build-dir", help="the build tree (default: build/)")
    ap.add_argument("--renderers", default="",
                    help="comma-separated: %s (default: all)"
                         % ",".join(a.name for a in renderers.ADAPTERS))
    ap.add_argument("--hard-renderers",
                    help="renderers of the hard cases (default: quick lmm_tracer,gl_shafts; "
                         "full: all)")
    ap.add_argument("--scale", type=float, help="image size factor (quick 0.5, full 1)")
    ap.add_argument("--ref-spp", type=int, help="reference spp (quick 512, full 4096)")
    ap.add_argument("--timeout", type=float, help="seconds before a run is stopped")
    ap.add_argument("--no-hard-cases", action="store_true", help="skip the hard cases")
    ap.add_argument("--no-twins", action="store_true",
                    help="skip the scenes' twins (validation/twins.py)")
    ap.add_argument("--retry-failed", action="store_true",
                    help="render again the runs that failed last time")
    ap.add_argument("--strict", action="store_true",
                    help="exit with status 1 if a hard-case check failed")
    ap.add_argument("--pages-only", action="store_true",
                    help="rewrite index.html and summary.md from DIR/results.json, "
                         "rendering nothing")
    ap.add_argument("-q", "--quiet", action="store_true", help="no progress messages")
    s = ap.add_argument_group("executor", "where the renders run (docs/validation.md, "
                              "'On a cluster')")
    s.add_argument("--executor", choices=("local", "slurm"), default="local",
                   help="local: here, one at a time (default); slurm: every render a "
                        "task of a Slurm job array, then compared here")
    s.add_argument("--partition", help="Slurm partition (default: the cluster's)")
    s.add_argument("--account", help="Slurm account to charge")
    s.add_argument("--slurm-parallel", type=int, default=32, metavar="N",
                   help="at most N tasks of an array at once (default 32)")
    s.add_argument("--slurm-retries", type=int, default=2, metavar="N",
                   help="resubmit a task that failed on Slurm's side N times (default 2)")
    s.add_argument("--slurm-cpus", type=int, default=1, metavar="N",
                   help="CPUs per task (default 1)")
    s.add_argument("--slurm-setup", metavar="FILE",
                   help="shell lines every task runs first (module load, a container's "
                        "environment)")
    s.add_argument("--sbatch-arg", action="append", default=[], metavar="ARG",
                   help="one more sbatch option (repeatable), e.g. --sbatch-arg=--qos=low")
    args = ap.parse_args(argv)
    if args.executor == "local" and (args.partition or args.account or args.slurm_setup
                                     or args.sbatch_arg):
        ap.error("--partition, --account, --slurm-setup and --sbatch-arg need --executor slurm")
    if args.slurm_parallel < 1 or args.slurm_retries < 0 or args.slurm_cpus < 1:
        ap.error("--slurm-parallel and --slurm-cpus must be at least 1, "
                 "--slurm-retries at least 0")
    args.mode = args.mode or "quick"
    return args


def reclassify(results, root):
    """Gives the scenes of `results` (a results.json's dict) their verdicts
    again from their runs and today's causes (verdicts.CAUSES), so that
    --pages-only says what is known now of a run made before; a scene whose
    source file is gone keeps its verdicts. Returns how many scenes were
    judged again (a twin with its scene)."""
    entries = {e.get("name"): e for e in results.get("scenes", [])}
    done = 0
    for entry in results.get("scenes", []):
        if entry.get("twin_of") or entry.get("error") or not entry.get("source"):
            continue
        source = Path(entry["source"])
        try:
            data = json.loads((source if source.is_absolute() else root / source).read_bytes())
        except (OSError, ValueError):
            continue
        twin = entries.get((entry.get("twin") or {}).get("name"))
        made = make_twin(source.stem, data) if twin is not None else None
        if made is not None:
            twin["verdicts"] = verdicts.classify(twin, made[1],
                                                 ref_spp=results.get("reference_spp"))
            done += 1
        entry["verdicts"] = verdicts.classify(entry, data, twin=twin if made else None,
                                              ref_spp=results.get("reference_spp"))
        done += 1
    return done


def main(argv=None):
    args = parse_args(argv)
    started = time.time()
    say = (lambda m: None) if args.quiet else (lambda m: print(m, flush=True))
    if args.pages_only:
        try:
            results = json.loads((Path(args.report) / "results.json").read_text())
        except (OSError, ValueError) as e:
            print("validate: cannot read %s/results.json: %s" % (args.report, e), file=sys.stderr)
            return 2
        reclassified = reclassify(results, HERE.parent)
        report.write_html(results, args.report)
        write_atomic(Path(args.report) / "summary.md", report.summary_markdown(results))
        say("rewrote %s/index.html and summary.md (verdicts of %d scenes from today's "
            "causes)" % (args.report, reclassified))
        return 0
    root = HERE.parent
    # Absolute: the renderers run in their own work directories.
    build = Path(args.build_dir or root / "build").resolve()
    mode = MODES[args.mode]
    ctx = renderers.Context(root, build, mode=args.mode, timeout=args.timeout, say=say,
                            warm_frames=mode["warm_frames"])
    if not ctx.tool("validation/shafts_compare").exists() or renderers.REFERENCE.missing(ctx):
        print("validate: build first (make build): %s needs lmm_tracer and shafts_compare"
              % build, file=sys.stderr)
        return 2
    try:
        wanted = renderers.by_name(args.renderers)
        hard_wanted = renderers.by_name(args.hard_renderers if args.hard_renderers is not None
                                        else mode["hard"])
    except ValueError as e:
        print("validate: %s" % e, file=sys.stderr)
        return 2
    scene_files = find_scenes(args.scenes, root / "scenes")
    if not scene_files:
        print("validate: no scene files found", file=sys.stderr)
        return 2
    report_dir = Path(args.report)
    report_dir.mkdir(parents=True, exist_ok=True)
    cache = RunCache(Path(args.cache) if args.cache else build / "validation-cache")

    available, infos = [], []
    for a in renderers.ADAPTERS:
        if a not in wanted and a not in hard_wanted:
            continue
        note = a.missing(ctx)
        info = {"name": a.name, "label": a.label, "colour": a.colour, "about": a.about,
                "available": note is None, "note": note}
        if note is None:
            info["version"] = a.version(ctx)
            if a in wanted:
                available.append(a)
        else:
            say("skipping %s: %s" % (a.name, note))
        infos.append(info)

    ref_spp = args.ref_spp or mode["ref_spp"]
    results = {"mode": args.mode, "date": time.strftime("%Y-%m-%d %H:%M:%S"),
               "machine": machine(), "reference_spp": ref_spp, "lit": LIT,
               "command": command_line(argv), "commit": source_commit(root),
               "renderers": infos, "scenes": [], "hard_cases": None}
    if args.executor == "slurm":
        executor = slurm.SlurmExecutor(
            ctx, cache, args.retry_failed, partition=args.partition, account=args.account,
            parallel=args.slurm_parallel, retries=args.slurm_retries, cpus=args.slurm_cpus,
            setup=args.slurm_setup, sbatch_args=args.sbatch_arg)
    else:
        executor = LocalExecutor(ctx, cache, args.retry_failed)
    val = Validation(ctx, cache, report_dir, available, ref_spp, executor, say,
                     twins=not args.no_twins)
    # --scale sets every scene's; else the mode's, or the scene's own
    # in that mode (scenes.SCENE_MODES).
    def scale_of(path):
        return args.scale if args.scale is not None else mode_scale(path, args.mode,
                                                                     mode["scale"])
    hard = [a for a in hard_wanted if a.missing(ctx) is None]
    # Every run of the validation, planned ahead: the Slurm executor renders
    # them first (the comparisons below then read them from the cache), and
    # the progress messages count them and estimate the time left.
    planned = [r for path in scene_files for r in val.planned(path, scale_of(path))]
    if not args.no_hard_cases:
        planned += hard_cases.planned_runs(ctx, hard, cache)
    if args.executor == "slurm":
        try:
            executor.prefetch(planned, say)
        except slurm.SlurmError as e:
            print("validate: %s" % e, file=sys.stderr)
            return 2
    executor = val.executor = ProgressExecutor(executor, cache, planned, args.retry_failed)
    say("%d renderings, %d of them in the cache" % (executor.total, len(executor.done)))
    results["executor"] = executor.info()

    def save():
        results["elapsed_seconds"] = time.time() - started
        results["rendered"], results["cached"] = val.rendered, val.cached
        results["render_seconds"] = render_seconds(results)
        write_atomic(report_dir / "results.json", json.dumps(results, indent=1) + "\n")
        report.write_html(results, report_dir)
        write_atomic(report_dir / "summary.md", report.summary_markdown(results))

    for path in scene_files:
        entry = val.scene(path, scale_of(path))
        results["scenes"].append(entry)
        save()
        twin = val.twin(path, scale_of(path), entry) if val.twins else None
        if twin:
            results["scenes"].append(twin)
            save()

    if not args.no_hard_cases:
        say("hard cases (%s)" % ", ".join(a.name for a in hard))
        with tempfile.TemporaryDirectory(prefix="validate-hard.") as tmp:
            hc = hard_cases.run_suite(ctx, hard, cache, tmp, say=lambda m: say("  " + m),
                                      image_dir=report_dir / "hard", executor=executor)
        results["hard_cases"] = hc
    save()

    say("")
    for s in results["scenes"]:
        if s.get("error"):
            say("%-24s %s" % (s["name"], s["error"]))
            continue
        for name, tt in s["time_to"].items():
            best = tt.get("best")
            say("%-24s %-23s least error %-8s  to 5%%: %-9s to 2%%: %-9s to 1%%: %s" % (
                s["name"], report.series_label(val.labels, name, s["time_to"]),
                fmt_percent(best[0]) if best else "-",
                fmt_seconds(tt.get("0.05")), fmt_seconds(tt.get("0.02")), fmt_seconds(tt.get("0.01"))))
    failed = results["hard_cases"]["failures"] if results["hard_cases"] else []
    if results["hard_cases"]:
        say("hard cases: %d failed checks" % len(failed))
        for f in failed:
            say("  FAIL %s / %s %s: %s: %s" % f)
    say("report: %s" % (report_dir / "index.html"))
    no_reference = [s["name"] for s in results["scenes"] if s.get("error")]
    if results["hard_cases"]:
        no_reference += [c["name"] for c in results["hard_cases"]["cases"] if c.get("error")]
    if no_reference:
        say("the reference failed for: %s" % ", ".join(no_reference))
        return 1
    if getattr(executor, "failed", None):
        say("%d Slurm tasks failed (above); their runs are not cached: run again to "
            "render only them" % len(executor.failed))
        return 1
    return 1 if (args.strict and failed) else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        print("validate: interrupted; finished runs are cached, run again to resume",
              file=sys.stderr)
        sys.exit(130)
