"""The renderers the validation compares, one adapter each.

An adapter knows how to tell whether its renderer is there (and why not,
for the report), what version it is (part of every run's cache key), which
settings to sweep in each validation mode, how to render one scene at one
setting, and how to read the renderer's own timing. Adding a renderer is
adding an entry to ADAPTERS; one that is missing or fails is skipped with a
note in the report, and the rest of the validation goes on.

Timing: `wall_seconds` is measured by the orchestrator around the render
command alone (not around exporting the scene); `tool_seconds` is the
renderer's own figure where it prints one (lmm_tracer's and gl_shafts'
--stats, POV-Ray's parse and trace times, Blender's frame time), which
leaves out process start-up. The report plots tool_seconds where there is
one, since start-up (two seconds for Blender) says nothing about a method.
"""

import json
import math
import os
import re
import shutil
import subprocess
from pathlib import Path

from .runs import NotExported, RunFailed, command, file_fingerprint

HERE = Path(__file__).resolve().parent


class Context:
    """What every adapter needs: where things are, the mode, limits."""

    def __init__(self, root, build, mode="quick", timeout=None, say=print, warm_frames=0):
        self.root = Path(root).resolve()
        self.build = Path(build).resolve()
        self.mode = mode
        self.timeout = timeout or (900 if mode == "quick" else 3600)
        self.say = say
        # Renderers that can also render in-process (gl_shafts) time that
        # many warm frames after each run (0: only the command line).
        self.warm_frames = warm_frames
        self._versions = {}

    def tool(self, rel):
        """A program of the build tree (build/rel)."""
        return self.build / rel

    def memo(self, key, compute):
        """compute() once per context, for version look-ups."""
        if key not in self._versions:
            self._versions[key] = compute()
        return self._versions[key]


def _executable(path):
    return Path(path).is_file() and os.access(path, os.X_OK)


def _export_missing(ctx, program):
    """Why a renderer reached through scene_export cannot run: the exporter
    not built, or `program` not installed; None when both are there."""
    if not _executable(ctx.tool(EXPORTER)):
        return "%s is not built" % ctx.tool(EXPORTER)
    if not shutil.which(program):
        return "%s is not installed (tools/bootstrap.sh installs it)" % program
    return None


def _stats_seconds(path, key="seconds"):
    """The `seconds` figure of a --stats JSON file, or None."""
    try:
        return float(json.loads(Path(path).read_text())[key])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _system_version(ctx, program, args=("--version",)):
    """The first line of `program --version` that names a version, and the
    binary's size and modification time (a package upgrade changes them)."""
    def compute():
        path = shutil.which(program)
        if not path:
            return "missing"
        real = os.path.realpath(path)
        st = os.stat(real)
        try:
            out = subprocess.run([path, *args], stdout=subprocess.PIPE,
                                 stderr=subprocess.STDOUT, timeout=60,
                                 check=False).stdout.decode(errors="replace")
        except (OSError, subprocess.TimeoutExpired):
            out = ""
        # The first line with a version number of three parts ("POV-Ray
        # 3.7.0.10", "Blender 3.4.1"), not a path that holds "3.7".
        line = next((l.strip() for l in out.splitlines()
                     if re.search(r"(?<![/.\d])\d+\.\d+\.\d+", l)), "")
        return "%s (%d bytes, mtime %d)" % (line, st.st_size, int(st.st_mtime))
    return ctx.memo(("system", program), compute)


def _build_version(ctx, rel):
    path = ctx.tool(rel)
    return ctx.memo(("build", rel), lambda: file_fingerprint(path)
                    if path.exists() else "missing")


class Adapter:
    """The interface every renderer implements (see the module's text)."""

    name = ""
    label = ""
    colour = "#000000"
    # What the report says about the renderer's relation to the reference.
    about = ""
    # The smallest image side the renderer can render, and why; the hard
    # cases skip (and report) what is smaller.
    min_image_side = 1
    min_image_why = ""

    # The cost model of the Slurm executor's per-task limits (limits()):
    # seconds to start, seconds per megapixel per unit of work(), and
    # memory. Measured on this machine (2 threads of a shared CPU) and made
    # generous: a task stopped by its limit is a Slurm failure, not a
    # measurement.
    startup_seconds = 2.0
    seconds_per_megapixel = 10.0
    memory_mb = 512
    memory_mb_per_megapixel = 1024

    def missing(self, ctx):
        """None if the renderer can run, else a sentence saying why not."""
        raise NotImplementedError

    def work(self, params):
        """How much a setting costs relative to the renderer's unit (1 spp,
        100 planes, ...): a setting of twice the work takes twice as long."""
        return 1.0

    def limits(self, ctx, scene, params):
        """The time (seconds) and memory (MB) a Slurm task rendering
        `scene` at `params` asks for: 20 times the cost model's estimate,
        at least 5 minutes, at most the run's own timeout, plus a minute to
        start; memory in steps of 64 MB."""
        megapixels = scene.width * scene.height / 1e6
        estimate = self.startup_seconds + megapixels * self.work(params) * self.seconds_per_megapixel
        seconds = min(ctx.timeout, max(300.0, 20.0 * estimate)) + 60.0
        mb = self.memory_mb + self.memory_mb_per_megapixel * megapixels
        return int(math.ceil(seconds)), int(math.ceil(mb / 64.0)) * 64

    def version(self, ctx):
        raise NotImplementedError

    def settings(self, ctx, scene):
        """The sweep for this scene in ctx.mode: a list of (label, params)."""
        raise NotImplementedError

    def hard_case_settings(self, ctx):
        """The settings the hard-case suite renders every case with: a list
        of (kind, label, params), kind "user" for the setting a user would
        choose and "converged" for the renderer's accuracy limit."""
        raise NotImplementedError

    def render(self, ctx, scene_path, params, work, log):
        """Renders into the directory `work`; returns a dict with image,
        wall_seconds and tool_seconds. Raises RunFailed."""
        raise NotImplementedError


# ---------------------------------------------------------------------------
# lmm_tracer: the reference itself, Whitted ray tracing and light meshes.

class LmmTracer(Adapter):
    name = "lmm_tracer"
    label = "lmm_tracer"
    colour = "#1f77b4"
    about = ("the project's ray tracer: reference mode at rising spp (the "
             "same integrator as the ground truth, another seed), whitted "
             "(the RRTA baseline) and lmm (light meshes: soft shadows, so it "
             "differs from the hard-shadowed reference by design)")
    TOOL = "lmm_tracer/lmm_tracer"
    # 0.5 s for 320x240 at 16 spp, reference mode (teapot_spot, 2 threads):
    # 0.4 s per megapixel and spp; 150 MB resident.
    seconds_per_megapixel = 2.0

    SWEEP = {
        "quick": {"spp": (1, 4, 16, 64), "extra": [("whitted, spp 4", {"mode": "whitted", "spp": 4}),
                                               ("lmm, spp 4", {"mode": "lmm", "spp": 4})]},
        "full": {"spp": (1, 2, 4, 8, 16, 32, 64, 128, 256),
                 "extra": [("whitted, spp 16", {"mode": "whitted", "spp": 16}),
                           ("lmm, spp 16", {"mode": "lmm", "spp": 16})]},
    }

    def missing(self, ctx):
        if not _executable(ctx.tool(self.TOOL)):
            return "%s is not built" % ctx.tool(self.TOOL)
        return None

    def version(self, ctx):
        return _build_version(ctx, self.TOOL)

    def settings(self, ctx, scene):
        sweep = self.SWEEP[ctx.mode]
        spps = sweep["spp"] if scene.has_medium else sweep["spp"][:1]
        out = [("reference, spp %d" % s, {"mode": "reference", "spp": s, "seed": 1})
               for s in spps]
        for label, params in sweep["extra"]:
            out.append((label, dict(params, seed=1)))
        return out

    def work(self, params):
        return float(params.get("spp", 16))

    def hard_case_settings(self, ctx):
        spp = 64 if ctx.mode == "quick" else 256
        return [("user", "spp %d" % spp, {"mode": "reference", "spp": spp, "seed": 1})]

    def render(self, ctx, scene_path, params, work, log):
        out, stats = work / "out.exr", work / "stats.json"
        cmd = [ctx.tool(self.TOOL), scene_path, "-o", out, "--mode", params["mode"],
               "--spp", params["spp"], "--seed", params.get("seed", 0),
               "--stats", stats, "-q"]
        wall, _ = command(cmd, cwd=work, timeout=ctx.timeout, log=log)
        return {"image": out, "wall_seconds": wall, "tool_seconds": _stats_seconds(stats)}


# ---------------------------------------------------------------------------
# gl_shafts: the plane-sweep renderer on OSMesa.

class GlShafts(Adapter):
    name = "gl_shafts"
    label = "gl_shafts"
    colour = "#d62728"
    about = ("the project's plane-sweep renderer (Dobashi et al. 2000) on "
             "OSMesa: its default, and sweeps over the number of planes, xi "
             "per fragment (--xi exact) or on the lattice (the paper's "
             "method) at several lattice sizes, and --jitter")
    TOOL = "gl_shafts/gl_shafts"
    # The in-process bench: the warm frame (docs/gl_shafts.md).
    BENCH = "gl_shafts/gl_shafts_bench"
    # 1.5 s for 320x240 at 100 planes, most of it starting llvmpipe and
    # compiling shaders; 250 MB resident. Work: planes / 100.
    startup_seconds = 5.0
    memory_mb = 768
    # Every setting but "default" names its --xi, so that a change of
    # gl_shafts' defaults cannot change what a label means.
    SWEEP = {
        "quick": [("default", {}),
                  ("planes 25, xi exact", {"planes": 25, "xi": "exact"}),
                  ("planes 100, xi lattice 20x20", {"planes": 100, "xi": "lattice"})],
        "full": ([("default", {})]
                 + [("planes %d, xi exact" % p, {"planes": p, "xi": "exact"})
                    for p in (12, 25, 50, 100, 200, 400, 800)]
                 + [("planes %d, xi lattice 20x20" % p, {"planes": p, "xi": "lattice"})
                    for p in (25, 100, 400)]
                 + [("planes 100, xi lattice %dx%d" % (n, n),
                     {"planes": 100, "xi": "lattice", "lattice": [n, n]}) for n in (4, 8, 40)]
                 + [("planes %d, xi exact, jitter" % p, {"planes": p, "xi": "exact", "jitter": True})
                    for p in (25, 100)]),
    }

    def missing(self, ctx):
        if not _executable(ctx.tool(self.TOOL)):
            return ("%s is not built (gl_shafts needs the EGL and GL "
                    "headers: Debian's libegl-dev and libgl-dev)" % ctx.tool(self.TOOL))
        return None

    def version(self, ctx):
        if not ctx.warm_frames:
            return _build_version(ctx, self.TOOL)
        # The warm frame is part of what a run records.
        return "%s; warm frame: %s, median of %d" % (
            _build_version(ctx, self.TOOL), _build_version(ctx, self.BENCH), ctx.warm_frames)

    # The atmosphere is drawn with 1 to 64 sampling planes (the sky) or
    # spheres (the planet from space); neither --xi nor --lattice applies
    # (its lattice step follows the camera; docs/gl_shafts.md, "The
    # atmosphere"). "xi exact" stays in the labels so that the planes form
    # the sweep verdicts.py reads.
    ATMOSPHERE_SWEEP = {
        "quick": [("default", {}), ("planes 4, xi exact", {"planes": 4, "xi": "exact"}),
                  ("planes 32, xi exact", {"planes": 32, "xi": "exact"})],
        "full": [("default", {})] + [("planes %d, xi exact" % p, {"planes": p, "xi": "exact"})
                                     for p in (2, 4, 8, 16, 32, 64)],
    }

    def settings(self, ctx, scene):
        sweep = self.SWEEP[ctx.mode]
        if not scene.has_medium:
            # Without a medium there is no sweep: one render says it all.
            return sweep[:1]
        if scene.medium_type == "atmosphere":
            return list(self.ATMOSPHERE_SWEEP[ctx.mode])
        return list(sweep)

    def work(self, params):
        return params.get("planes", 100) / 100.0

    def hard_case_settings(self, ctx):
        return [("user", "default", {}),
                ("converged", "planes 400, xi exact", {"planes": 400, "xi": "exact"})]

    @staticmethod
    def _options(params):
        """The settings as options, the same for gl_shafts and its bench."""
        opts = []
        if "planes" in params:
            opts += ["--planes", params["planes"]]
        if "lattice" in params:
            opts += ["--lattice", params["lattice"][0], params["lattice"][1]]
        if "xi" in params:
            opts += ["--xi", params["xi"]]
        if params.get("jitter"):
            opts += ["--jitter"]
        return opts

    def render(self, ctx, scene_path, params, work, log):
        """The image and the first image's time from the command line
        (tool_seconds: what a one-off user waits for, shader compilation
        included); with ctx.warm_frames, also the warm frame of the same
        setting rendered in-process (warm_seconds: the median of that many
        frames after a warm-up one, what a viewport or an animation pays per
        frame)."""
        out, stats = work / "out.exr", work / "stats.json"
        cmd = [ctx.tool(self.TOOL), scene_path, "-o", out, "--stats", stats, "-q"]
        wall, _ = command(cmd + self._options(params), cwd=work, timeout=ctx.timeout, log=log)
        result = {"image": out, "wall_seconds": wall, "tool_seconds": _stats_seconds(stats)}
        if ctx.warm_frames:
            result.update(self._warm(ctx, scene_path, params, work, log))
        return result

    def _warm(self, ctx, scene_path, params, work, log):
        """warm_seconds and warm_best_seconds from gl_shafts_bench, or a
        note why there are none (the image still counts)."""
        cmd = [ctx.tool(self.BENCH), scene_path, "--frames", ctx.warm_frames,
               "--ref-spp", 0] + self._options(params)
        try:
            _, text = command(cmd, cwd=work, timeout=ctx.timeout, log=log)
        except RunFailed as e:
            return {"notes": "no warm frame: %s" % e}
        times = _bench_frame_ms(text)
        if times is None:
            return {"notes": "no warm frame: gl_shafts_bench printed no frame time"}
        return {"warm_best_seconds": times[0] / 1000.0, "warm_seconds": times[1] / 1000.0}


def _bench_frame_ms(text):
    """(best, median) milliseconds per frame from gl_shafts_bench's table
    (its column "ms/frame: best (median)"), or None."""
    rows = [[c.strip() for c in line.strip().strip("|").split("|")]
            for line in text.splitlines() if line.startswith("|")]
    if len(rows) < 3:
        return None
    try:
        col = rows[0].index("ms/frame: best (median)")
        m = re.match(r"([\d.]+)\s*\(([\d.]+)\)", rows[2][col])
    except (ValueError, IndexError):
        return None
    return (float(m.group(1)), float(m.group(2))) if m else None


# ---------------------------------------------------------------------------
# The independent renderers, through scene_export.

EXPORTER = "scene_export/scene_export"


# What scene_export says when it refuses a scene for a target (se_run.c:
# "the blender exporter does not write a medium of type 'atmosphere' yet",
# also in the add-on's import, which runs the same writer), and what the
# exported Blender script says when it refuses the scene for one engine
# (blender_build.py: "EEVEE does not render a planet's atmosphere (...)").
REFUSAL = re.compile(r"the \w+ exporter does not write [^;|]*|\bEEVEE does not render [^;|]*")


def _refused(error):
    """A RunFailed turned into NotExported when its message is the
    exporter's refusal; else the error itself."""
    m = REFUSAL.search(str(error))
    return NotExported(m.group(0).strip()) if m else error


def _export(ctx, scene_path, target, out, log, quality="final"):
    """Writes the scene for `target` into `out`; raises NotExported when the
    exporter refuses the scene, RunFailed when it fails."""
    try:
        command([ctx.tool(EXPORTER), scene_path, "--to", target, "--quality", quality,
                 "-o", out], cwd=out.parent, timeout=300, log=log)
    except RunFailed as e:
        raise _refused(e) from e


def _time_sum(text, pattern):
    """The sum of the numbers a regular expression's group 1 finds."""
    found = [float(m) for m in re.findall(pattern, text)]
    return sum(found) if found else None


def pov_frames(work, name="scene", log=None):
    """The image POV-Ray's render of NAME.ini in `work` stands for: NAME.exr,
    or, for a scene scene_export renders in frames (an atmosphere with Mie
    scattering, a phase exported as several lobes: docs/scene_export.md),
    the signed sum of NAME1.exr, NAME2.exr, ... written to NAME.exr by
    oiiotool (OpenImageIO's, float sum of the half-float frames): a frame is
    subtracted where the .ini's `; Frame_Signs=+ + -` line says `-` (a lobe
    of negative weight, rendered with its |weight|). None if POV-Ray wrote
    neither."""
    work = Path(work)
    image = work / (name + ".exr")
    frames = []
    while (work / ("%s%d.exr" % (name, len(frames) + 1))).exists():
        frames.append(work / ("%s%d.exr" % (name, len(frames) + 1)))
    if len(frames) >= 2:
        signs = ["+"] * len(frames)
        ini = work / (name + ".ini")
        m = re.search(r"(?m)^; Frame_Signs=([+\- ]+)$", ini.read_text()) if ini.exists() else None
        if m:
            signs = m.group(1).split()
            if len(signs) != len(frames) or signs[0] != "+":
                raise RunFailed("%s's Frame_Signs (%s) do not match its %d frames"
                                % (ini.name, m.group(1), len(frames)))
        cmd = ["oiiotool", frames[0]]
        for f, sign in zip(frames[1:], signs[1:]):
            cmd += [f, "--sub" if sign == "-" else "--add"]
        command(cmd + ["-d", "float", "-o", image], cwd=work, log=log)
    return image if image.exists() else None


class PovRay(Adapter):
    name = "povray"
    label = "POV-Ray"
    colour = "#2ca02c"
    about = ("POV-Ray 3.7 through scene_export --to pov --quality final: "
             "media method 2 with jitter 0, a deterministic midpoint rule over "
             "`intervals` with `samples` per interval, both swept here (POV-Ray "
             "3.7 holds at most 255 intervals)")
    # (intervals, samples per interval); the last is the exporter's final.
    # Work: intervals x samples / 100.
    SWEEP = {"quick": ((25, 1), (100, 1)),
             "full": ((10, 1), (25, 1), (50, 1), (100, 1), (200, 1), (255, 4))}
    # Media with a density (height fog, the atmosphere) cost the square of
    # the samples along a ray: every sample's shadow ray to the light is
    # sampled with the same intervals and samples (POV-Ray has no closed
    # form for a density's optical depth, as it has for constant media).
    # Measured on valley_fog at 40x30, CPU seconds: 10 intervals 0.12, 25
    # 0.23, 50 0.57, 100 2.0, 200 7.9, 255 11.8; 25 x 4 and 50 x 2 1.8 as
    # 100 x 1; so the exporter's final 255 x 4 would take about 190 s there
    # and over 12 min at 80x60. Their sweeps stop at 200 samples along a
    # ray (the quick one at 25), where the midpoint rule is within 0.3% on
    # the height fog and the atmosphere's error is its phase mixture.
    DENSITY_SWEEP = {"quick": ((10, 1), (25, 1)),
                     "full": ((10, 1), (25, 1), (50, 1), (100, 1), (200, 1))}
    # The atmosphere's eight media make every sample eight times dearer.
    ATMOSPHERE_SWEEP = {"quick": ((10, 1), (25, 1)),
                        "full": ((10, 1), (25, 1), (50, 1), (100, 1))}

    def missing(self, ctx):
        return _export_missing(ctx, "povray")

    def version(self, ctx):
        return "%s; scene_export %s" % (_system_version(ctx, "povray"),
                                        _build_version(ctx, EXPORTER))

    def settings(self, ctx, scene):
        if scene.medium_type == "atmosphere":
            values = self.ATMOSPHERE_SWEEP[ctx.mode]
        elif scene.medium_type == "height_fog":
            values = self.DENSITY_SWEEP[ctx.mode]
        else:
            values = self.SWEEP[ctx.mode] if scene.has_medium else self.SWEEP[ctx.mode][-1:]
        return [self._setting(n, k) for n, k in values]

    def work(self, params):
        return params["intervals"] * params["samples"] / 100.0

    @staticmethod
    def _setting(intervals, samples):
        label = "intervals %d" % intervals + (", %d samples" % samples if samples > 1 else "")
        return (label, {"intervals": intervals, "samples": samples})

    def hard_case_settings(self, ctx):
        return [("user",) + self._setting(255, 4)]

    def render(self, ctx, scene_path, params, work, log):
        _export(ctx, scene_path, "pov", work / "scene.pov", log)
        pov = work / "scene.pov"
        text = pov.read_text()
        text, n = re.subn(r"(?m)^(\s*intervals\s+)\d+", r"\g<1>%d" % params["intervals"], text)
        text, k = re.subn(r"(?m)^(\s*samples\s+)\d+\s*,\s*\d+",
                          r"\g<1>%d, %d" % (params["samples"], params["samples"]), text)
        if (n == 0 or k == 0) and re.search(r"\bmedia\s*\{", text):
            raise RunFailed("the exported .pov has media but no `intervals` or "
                            "`samples` line to set")
        pov.write_text(text)
        # POV-Ray wants a writable home for its user configuration.
        env = {"HOME": str(work)}
        wall, out = command(["povray", "scene.ini"], cwd=work, env=env,
                            timeout=ctx.timeout, log=log)
        tool = _time_sum(out, r"(?:Parse|Bounding|Photon|Radiosity|Trace) Time:.*?\(([\d.]+) seconds\)")
        image = pov_frames(work, "scene", log)
        if image is None:
            raise RunFailed("povray wrote no scene.exr (nor frames scene1.exr, scene2.exr, ...)")
        return {"image": image, "wall_seconds": wall, "tool_seconds": tool}


def _blender_frame_seconds(text):
    """Blender's ` Time: MM:SS.ss (Saving: ...)` lines, in seconds, summed
    (the exported script renders a chromatic height fog or atmosphere in
    Cycles once per colour channel)."""
    m = re.findall(r"^\s*Time:\s*(?:(\d+):)?(\d+):([\d.]+)", text, re.M)
    if not m:
        return None
    return sum(int(h or 0) * 3600 + int(mnt) * 60 + float(s) for h, mnt, s in m)


class _Blender(Adapter):
    """Shared by Cycles and EEVEE: export, run Blender, read its time."""

    # Blender starts in about two seconds and renders within 2 GB here.
    startup_seconds = 10.0
    memory_mb = 2048
    min_image_side = 4
    min_image_why = ("Blender renders at least 4 pixels a side: asked for 1x1 or 3x3, "
                     "Blender 3.4 writes a 4x4 image")

    def missing(self, ctx):
        return _export_missing(ctx, "blender")

    def _run_blender(self, ctx, prefix, engine, samples, work, log, env=None, pre=(),
                     seed=1, extra=()):
        py = work / "scene.py"
        out = work / "out.exr"
        cmd = list(prefix) + ["blender", "-b"]
        for p in pre:
            cmd += ["-P", p]
        cmd += ["-P", py, "--", "--engine", engine, "--out", out,
                "--samples", samples, "--seed", seed] + list(extra)
        try:
            wall, text = command(cmd, cwd=work, env=env, timeout=ctx.timeout, log=log)
        except RunFailed as e:
            raise _refused(e) from e
        if not out.exists():
            raise RunFailed("blender wrote no image")
        return {"image": out, "wall_seconds": wall,
                "tool_seconds": _blender_frame_seconds(text)}


class Cycles(_Blender):
    name = "cycles"
    label = "Cycles"
    colour = "#9467bd"
    about = ("Blender 3.4 Cycles through scene_export --to blender, single "
             "scattering, point-sampled pixels, at rising samples per pixel")
    SWEEP = {"quick": (4, 16), "full": (4, 16, 64, 256, 1024)}

    def work(self, params):
        return params["samples"] / 4.0

    def version(self, ctx):
        return "%s; scene_export %s" % (_system_version(ctx, "blender"),
                                        _build_version(ctx, EXPORTER))

    def settings(self, ctx, scene):
        return [("%d spp" % n, {"samples": n}) for n in self.SWEEP[ctx.mode]]

    def hard_case_settings(self, ctx):
        return [("user", "64 spp", {"samples": 64})]

    def render(self, ctx, scene_path, params, work, log):
        _export(ctx, scene_path, "blender", work / "scene.py", log)
        # A second seed (validation/peers.py) measures Cycles' noise;
        # one_pass renders a chromatic ray-marched medium in one pass, as
        # Cycles does (validation/cycles_channels.py measures its bias).
        return self._run_blender(ctx, [], "cycles", params["samples"], work, log,
                                 seed=params.get("seed", 1),
                                 extra=["--one-pass"] if params.get("one_pass") else [])


EEVEE_SCRIPT = HERE / "blender_eevee.py"


class Eevee(_Blender):
    name = "eevee"
    label = "EEVEE"
    colour = "#ff7f0e"
    about = ("Blender 3.4 EEVEE (real-time volumetrics on llvmpipe under "
             "xvfb-run) through scene_export --to blender, with the "
             "volumetric tile size and samples swept by "
             "validation/blender_eevee.py")
    # (tile size in pixels, volumetric samples, volumetric shadow samples,
    # TAA render samples). The quick sweep's one point is the full sweep's
    # most accurate, within half a point of mean_rel of the exported
    # script's final setting on the hard cases' base scene (7.3% against
    # 6.9%; tile 8 and TAA 1: 55%); the full sweep's cheaper points are its
    # speed-against-error curve (scene_export/eevee_limits.py --part
    # surfaces; docs/validation.md, "The renderers and their sweeps").
    SWEEP = {"quick": ((2, 128, 64, 8),),
             "full": ((16, 16, 8, 1), (8, 32, 16, 1), (4, 64, 32, 4), (2, 128, 64, 8))}

    def missing(self, ctx):
        note = super().missing(ctx)
        if note:
            return note
        if not shutil.which("xvfb-run"):
            return "xvfb-run is not installed (EEVEE needs a display; Debian's xvfb)"
        return None

    def version(self, ctx):
        return "%s; scene_export %s; override %s" % (
            _system_version(ctx, "blender"), _build_version(ctx, EXPORTER),
            file_fingerprint(EEVEE_SCRIPT))

    def settings(self, ctx, scene):
        if not scene.has_medium and ctx.mode == "quick":
            # EEVEE is here for its volumetrics, and it is the slowest peer
            # (shader compilation on llvmpipe): the quick mode leaves it out
            # of scenes without a medium.
            return []
        sweep = self.SWEEP[ctx.mode] if scene.has_medium else self.SWEEP[ctx.mode][:1]
        return [("tile %d, %d samples, TAA %d" % (t, s, a),
                 {"tile": t, "samples": s, "shadow_samples": ss, "taa": a})
                for t, s, ss, a in sweep]

    # xvfb-run and shader compilation on llvmpipe come on top of Blender.
    startup_seconds = 60.0
    memory_mb = 3072

    def work(self, params):
        if params.get("exported"):
            # The script's own settings: tile 2 px, 256 slices.
            return 256 / 8.0 * params["taa"] * 16.0
        return params["samples"] / 8.0 * params["taa"] * (8.0 / params["tile"]) ** 2

    def hard_case_settings(self, ctx):
        # What a user gets: the exported script's own volumetric settings
        # (tile 2 px, 256 slices, 32 shadow samples) at its draft TAA 16, as
        # validation.peers renders: 7.0% mean_rel on the hard cases' base
        # scene against 6.9% at TAA 64 in half the time, and 55% at tile 8
        # and TAA 1 (scene_export/eevee_limits.py --part surfaces).
        return [("user", "exported settings, TAA 16", {"exported": True, "taa": 16})]

    def render(self, ctx, scene_path, params, work, log):
        _export(ctx, scene_path, "blender", work / "scene.py", log)
        prefix = ["xvfb-run", "-a", "-s", "-screen 0 640x480x24"]
        if params.get("exported"):
            # The exported script's own volumetric settings (docs/
            # scene_export.md, "EEVEE"), TAA samples from the command line.
            return self._run_blender(ctx, prefix, "eevee", params["taa"], work, log)
        env = {"SHAFTS_EEVEE_SETTINGS": json.dumps({
            "volumetric_tile_size": str(params["tile"]),
            "volumetric_samples": params["samples"],
            "volumetric_shadow_samples": params["shadow_samples"],
            "taa_render_samples": params["taa"]})}
        return self._run_blender(ctx, prefix, "eevee", params["taa"], work, log,
                                 env=env, pre=[EEVEE_SCRIPT])


# ---------------------------------------------------------------------------
# The Blender add-on's engines: the scene imported as a user imports it,
# rendered by F12 inside Blender (validation/blender_addon_render.py).

ADDON_SCRIPT = HERE / "blender_addon_render.py"


class _Addon(Adapter):
    """Shared by the add-on's two engines."""

    ZIP = "shafts_blender.zip"
    LIB = "libshafts.so"
    ENGINE = ""
    startup_seconds = 10.0
    memory_mb = 1024
    min_image_side = _Blender.min_image_side
    min_image_why = _Blender.min_image_why

    def missing(self, ctx):
        for rel in (self.ZIP, self.LIB):
            if not ctx.tool(rel).is_file():
                return "%s is not built (make addon)" % ctx.tool(rel)
        return _export_missing(ctx, "blender")

    def version(self, ctx):
        # The exporter probes the scene first (render): a new one that
        # writes what the old refused renders the scene again.
        return "%s; add-on %s; libshafts %s; script %s; scene_export %s" % (
            _system_version(ctx, "blender"), _build_version(ctx, self.ZIP),
            _build_version(ctx, self.LIB), file_fingerprint(ADDON_SCRIPT),
            _build_version(ctx, EXPORTER))

    def render(self, ctx, scene_path, params, work, log):
        out, settings = work / "out.exr", work / "settings.json"
        settings.write_text(json.dumps(params))
        # The import runs the Blender exporter's writer: a scene it refuses
        # is "not exported", known before Blender starts.
        _export(ctx, scene_path, "blender", work / "probe.py", log)
        # Debian's Blender finds its Python's library through the first
        # python3 on PATH: another one first (pyenv's) hides the system's
        # numpy, which the add-on imports. The directory of blender comes
        # first, so Blender gets the Python it was built with.
        blender_dir = os.path.dirname(os.path.realpath(shutil.which("blender")))
        env = {"BLENDER_USER_SCRIPTS": str(work / "scripts"),
               "BLENDER_USER_CONFIG": str(work / "config"),
               "SHAFTS_LIB": str(ctx.tool(self.LIB)),
               "PATH": blender_dir + os.pathsep + os.environ.get("PATH", "")}
        (work / "scripts" / "addons").mkdir(parents=True)
        (work / "config").mkdir()
        cmd = ["blender", "-b", "--factory-startup", "--python-exit-code", 1,
               "--python", ADDON_SCRIPT, "--", ctx.tool(self.ZIP), scene_path, out,
               self.ENGINE, settings]
        try:
            wall, text = command(cmd, cwd=work, env=env, timeout=ctx.timeout, log=log)
        except RunFailed as e:
            raise _refused(e) from e
        if not out.exists():
            raise RunFailed("blender wrote no image")
        m = re.findall(r"^shafts_addon_render_seconds: ([\d.]+)", text, re.M)
        return {"image": out, "wall_seconds": wall,
                "tool_seconds": float(m[-1]) if m else None}


class AddonSweep(_Addon):
    name = "addon_sweep"
    label = "add-on: Shafts Sweep"
    colour = "#8c564b"
    about = ("the Blender add-on's Shafts Sweep engine (gl_shafts in Blender): the "
             "scene imported with File > Import > Shafts scene, F12 at the engine's "
             "defaults; its time is F12 alone")
    ENGINE = "SHAFTS_SWEEP"

    def settings(self, ctx, scene):
        return [("default", {})]

    def hard_case_settings(self, ctx):
        return [("user", "default", {})]


class AddonTracer(_Addon):
    name = "addon_tracer"
    label = "add-on: Shafts Tracer"
    colour = "#e377c2"
    about = ("the Blender add-on's Shafts Tracer engine (lmm_tracer in Blender), "
             "reference mode, the scene imported with File > Import > Shafts scene; "
             "its time is F12 alone")
    ENGINE = "SHAFTS_TRACER"
    seconds_per_megapixel = 2.0
    SPP = {"quick": (16,), "full": (16, 64)}

    def work(self, params):
        return float(params.get("spp", 16))

    def settings(self, ctx, scene):
        return [("reference, spp %d" % n, {"mode": "REFERENCE", "spp": n})
                for n in self.SPP[ctx.mode]]

    def hard_case_settings(self, ctx):
        return [("user", "reference, spp 16", {"mode": "REFERENCE", "spp": 16})]


# The table: every renderer the validation knows, in the report's order.
ADAPTERS = [LmmTracer(), GlShafts(), PovRay(), Cycles(), Eevee(), AddonSweep(), AddonTracer()]
REFERENCE = ADAPTERS[0]


def by_name(names):
    """The adapters named in a comma-separated list (all if empty)."""
    if not names:
        return list(ADAPTERS)
    wanted = [n.strip() for n in names.split(",") if n.strip()]
    known = {a.name: a for a in ADAPTERS}
    unknown = [n for n in wanted if n not in known]
    if unknown:
        raise ValueError("unknown renderer(s) %s; known: %s"
                         % (", ".join(unknown), ", ".join(known)))
    return [known[n] for n in wanted]
