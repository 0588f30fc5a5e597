"""Unit tests of the validation scripts' own logic (no renderer needed):
the Pareto front and time-to-error, the scene content key, the run cache's
resume behaviour, the hard cases' scene scaling and projection, the SVG
plot and the report pages, and POV-Ray's frames summed with their signs
(pov_frames, with OpenImageIO's oiiotool). Run from the source tree:
python3 -m validation.test_validate."""

import json
import math
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

from . import atmo_phase_bias, renderers, report, slurm
from .hard import bounds as hard_bounds
from .hard import cases as hard_cases
from .hard import runner as hard_runner
from .metrics import fmt_number, fmt_percent, fmt_seconds, pareto_front, time_to_reach
from .progress import ProgressExecutor, fmt_left
from .runs import NotExported, Run, RunCache, RunFailed, execute, run_key
from .scenes import (light_mask, mode_scale, prepare_data, project, referenced_files,
                     scaled_size)
from .svgplot import speed_error_svg

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent


class MetricsTest(unittest.TestCase):
    def test_pareto_front(self):
        pts = [(1, 0.5, "a"), (2, 0.1, "b"), (3, 0.2, "c"), (0.5, 0.9, "d"), (4, 0.05, "e"),
               (None, 0.01, "no time")]
        self.assertEqual([p[2] for p in pareto_front(pts)], ["d", "a", "b", "e"])

    def test_pareto_ties(self):
        # Of two points with equal time, the better error wins; equal error
        # later in time is dominated.
        pts = [(1, 0.2, "a"), (1, 0.1, "b"), (2, 0.1, "c")]
        self.assertEqual([p[2] for p in pareto_front(pts)], ["b"])

    def test_time_to_reach(self):
        pts = [(1, 0.08, ""), (2, 0.03, ""), (8, 0.015, ""), (5, 0.04, "")]
        self.assertEqual(time_to_reach(pts, 0.05), 2)
        self.assertEqual(time_to_reach(pts, 0.02), 8)
        self.assertIsNone(time_to_reach(pts, 0.01))

    def test_formats(self):
        self.assertEqual(fmt_seconds(0.0123), "12.3 ms")
        self.assertEqual(fmt_seconds(12.34), "12.3 s")
        self.assertEqual(fmt_seconds(None), "–")
        self.assertEqual(fmt_percent(0.0123), "1.2 %")
        self.assertEqual(fmt_percent(0.35), "35 %")
        # People's numbers: no exponent anywhere.
        self.assertEqual(fmt_percent(1.8), "180 %")
        self.assertEqual(fmt_percent(123.0), "12,300 %")
        self.assertEqual(fmt_percent(0.0027), "0.27 %")
        self.assertEqual(fmt_percent(0.000123), "0.012 %")
        self.assertEqual(fmt_percent(1e-7), "< 0.01 %")
        self.assertEqual(fmt_percent(0.0), "0 %")
        self.assertEqual(fmt_percent(0.0999), "10 %")
        self.assertEqual(fmt_seconds(0.9997), "1.00 s")
        self.assertEqual(fmt_seconds(0.0996), "99.6 ms")
        self.assertEqual(fmt_seconds(0.00012), "120 µs")
        self.assertEqual(fmt_seconds(150.0), "150 s")
        self.assertEqual(fmt_seconds(1230.0), "20.5 min")
        self.assertEqual(fmt_number(0.0725), "0.0725")
        self.assertEqual(fmt_number(1234.5), "1,230")
        self.assertEqual(fmt_number(2.1e-5), "0.0000210")
        for v in (1e-9, 3e-5, 0.5, 2.0, 1e3, 1e5, 1e40):
            self.assertNotIn("e+", fmt_percent(v) + fmt_seconds(v))
            self.assertNotIn("e-", fmt_percent(v) + fmt_seconds(v))


class ScenesTest(unittest.TestCase):
    def test_key_follows_referenced_files(self):
        with tempfile.TemporaryDirectory() as d:
            d = Path(d)
            (d / "map.png").write_bytes(b"one")
            scene = {"camera": {"width": 40, "height": 30},
                     "lights": [{"light_map": {"image": "map.png"}}]}
            self.assertEqual(referenced_files(scene, d)[0][0], "lights[0].light_map.image")
            a = prepare_data("s", scene, d, d / "cache")
            b = prepare_data("s", scene, d, d / "cache")
            self.assertEqual(a.key, b.key)
            (d / "map.png").write_bytes(b"two")
            c = prepare_data("s", scene, d, d / "cache")
            self.assertNotEqual(a.key, c.key)
            half = prepare_data("s", scene, d, d / "cache", scale=0.5)
            self.assertNotEqual(c.key, half.key)
            self.assertEqual((half.width, half.height), (20, 15))
            derived = json.loads(half.path.read_text())
            # Its files are named relatively, copies in its own directory.
            image = derived["lights"][0]["light_map"]["image"]
            self.assertFalse(Path(image).is_absolute())
            self.assertEqual((half.path.parent / image).read_bytes(), b"two")

    def test_scaled_size(self):
        self.assertEqual(scaled_size(320, 240, 0.5), (160, 120))
        self.assertEqual(scaled_size(1, 1, 0.5, 8), (1, 1))
        self.assertEqual(scaled_size(20, 10, 0.1, 8), (8, 8))


class RunCacheTest(unittest.TestCase):
    def test_interrupted_run_is_redone_and_finished_run_is_kept(self):
        with tempfile.TemporaryDirectory() as d:
            cache = RunCache(d)
            key = run_key("scene", "r", "v1", {"x": 1})
            calls = []

            def interrupted(work, log):
                calls.append("interrupted")
                raise KeyboardInterrupt

            with self.assertRaises(KeyboardInterrupt):
                execute(cache, key, {"renderer": "r"}, interrupted)
            self.assertIsNone(cache.load(key))

            def render(work, log):
                calls.append("render")
                (work / "out.exr").write_bytes(b"image")
                return {"image": work / "out.exr", "wall_seconds": 1.5, "tool_seconds": 1.0}

            first = execute(cache, key, {"renderer": "r"}, render)
            self.assertEqual(first["status"], "ok")
            self.assertFalse(first["cached"])
            again = execute(cache, key, {"renderer": "r"}, render)
            self.assertTrue(again["cached"])
            self.assertEqual(again["tool_seconds"], 1.0)
            self.assertEqual(calls, ["interrupted", "render"])
            self.assertNotEqual(key, run_key("scene", "r", "v2", {"x": 1}))

    def test_failures_are_cached_unless_retried(self):
        with tempfile.TemporaryDirectory() as d:
            cache = RunCache(d)
            key = run_key("scene", "r", "v1", {})
            calls = []

            def fail(work, log):
                calls.append(1)
                raise RunFailed("broken")

            self.assertEqual(execute(cache, key, {}, fail)["error"], "broken")
            self.assertEqual(execute(cache, key, {}, fail)["status"], "failed")
            self.assertEqual(len(calls), 1)
            execute(cache, key, {}, fail, retry_failed=True)
            self.assertEqual(len(calls), 2)


class HardCasesTest(unittest.TestCase):
    def test_scaling_keeps_optical_depth_and_irradiance(self):
        base = hard_cases.base_scene(8, 6)
        s = hard_cases.scaled(base, 1e-3)
        self.assertAlmostEqual(s["medium"]["sigma_s"][0] * s["medium"]["bounds"]["max"][1],
                               base["medium"]["sigma_s"][0] * base["medium"]["bounds"]["max"][1])
        light, light0 = s["lights"][0], base["lights"][0]
        r = light["position"][1] - s["shapes"][0]["corner"][1]
        r0 = light0["position"][1] - base["shapes"][0]["corner"][1]
        self.assertAlmostEqual(light["intensity"][0] / r ** 2, light0["intensity"][0] / r0 ** 2)
        self.assertEqual(s["camera"]["fov_y_deg"], base["camera"]["fov_y_deg"])

    def test_projection_and_mask(self):
        scene = hard_cases.base_scene(65, 49)
        scene["camera"]["look_at"] = [0.0, 1.8, 0.0]
        scene["camera"]["position"] = [0.0, 1.8, 7.0]
        scene["lights"] = [{"type": "point", "position": [0.0, 1.8, 0.0]}]
        x, y = project(scene["camera"], [0.0, 1.8, 0.0])
        self.assertAlmostEqual(x, 32.5)
        self.assertAlmostEqual(y, 24.5)
        rects = light_mask(scene, radius=1.5)
        self.assertEqual(rects, [(31, 23, 3, 3)])
        self.assertIsNone(project(scene["camera"], [0.0, 1.8, 9.0]))

    def test_every_case_builds_a_valid_looking_scene(self):
        names = set()
        for case in hard_cases.CASES:
            w, h = hard_runner.case_size(case, "quick")
            s = case.build(w, h)
            self.assertEqual(s["format"], "shafts-scene")
            self.assertNotIn(case.name, names)
            names.add(case.name)
            for kind, other in case.invariance:
                self.assertIn(kind, ("scale", "position", "distance", "pixel", "plane"))
                self.assertIn(kind, hard_bounds.INVARIANCE_REASONS)
        for needed in ("point_light_in_view", "light_on_plane", "inside_spot_cone", "dense",
                       "thin", "planes_2000", "scale_1e-3", "scale_1e4", "murky_peak",
                       "grazing_directional", "hard_spot", "light_behind_camera", "image_1x1",
                       "scale_1e-9", "scale_1e9", "moved_1e6", "camera_500", "camera_5000"):
            self.assertIn(needed, names)

    def test_moved_and_camera_at(self):
        # moved() shifts every position and nothing else; camera_at() keeps
        # the half height framed at the look-at point.
        base = hard_cases.base_scene(8, 6)
        m = hard_cases.moved(base, (1e6, -1e6, 1e6))
        self.assertEqual(m["shapes"][1]["center"], [1e6 + 0.35, -1e6 + 2.4, 1e6 + 0.1])
        self.assertEqual(m["medium"]["bounds"]["min"], [1e6 - 2, -1e6, 1e6 - 2])
        self.assertEqual(m["lights"][0]["direction"], base["lights"][0]["direction"])
        self.assertEqual(m["medium"]["sigma_s"], base["medium"]["sigma_s"])
        c = base["camera"]
        half = (c["position"][2] - c["look_at"][2]) * math.tan(math.radians(c["fov_y_deg"] / 2))
        far = hard_cases.camera_at(5000.0)(8, 6)["camera"]
        self.assertAlmostEqual(far["position"][2], c["look_at"][2] + 5000.0)
        self.assertAlmostEqual(5000.0 * math.tan(math.radians(far["fov_y_deg"] / 2)), half)

    def test_dense_and_thin_optical_depths(self):
        cases = {c.name: c for c in hard_cases.CASES}
        for name, depth in (("dense", 50.0), ("thin", 1e-6)):
            m = cases[name].build(8, 6)["medium"]
            size = m["bounds"]["max"][0] - m["bounds"]["min"][0]
            self.assertTrue(math.isclose((m["sigma_s"][0] + m["sigma_a"][0]) * size, depth,
                                         rel_tol=1e-9))

    def test_input_cases_run_only_our_tools(self):
        # A full run's hard cases include the peers; the input cases ran
        # BUILD/povray/povray and stopped the run with FileNotFoundError.
        from .hard import inputs as hard_inputs

        class Ctx:
            def tool(self, rel):
                return "/build/" + rel

        class Adapter:
            def __init__(self, name):
                self.name = name
        names = ("lmm_tracer", "gl_shafts", "povray", "cycles", "eevee", "addon_sweep")
        tools = hard_inputs.cli_tools(Ctx(), [Adapter(n) for n in names])
        self.assertEqual(tools, {"lmm_tracer": "/build/lmm_tracer/lmm_tracer",
                                 "gl_shafts": "/build/gl_shafts/gl_shafts"})

    def test_bounds(self):
        self.assertEqual(hard_bounds.bound_for("lmm_tracer", "user", "dense", "quick"), 0.25)
        self.assertEqual(hard_bounds.bound_for("lmm_tracer", "user", "dense", "full"), 0.05)
        self.assertEqual(hard_bounds.bound_for("gl_shafts", "user", "dense", "quick"), 0.02)
        self.assertEqual(hard_bounds.bound_for("gl_shafts", "case", "base", "quick"),
                         hard_bounds.bound_for("gl_shafts", "user", "base", "quick"))
        self.assertIsNone(hard_bounds.bound_for("eevee", "user", "base", "full"))
        self.assertIsNone(hard_bounds.bound_for("unknown", "user", "base", "full"))
        # Black cases: 0 unless stated, and only black cases are stated.
        self.assertEqual(hard_bounds.black_bound("lmm_tracer", "light_in_box"), 0.0)
        self.assertEqual(hard_bounds.black_bound("gl_shafts", "closed_room"), 0.0)
        self.assertEqual(hard_bounds.black_bound("povray", "closed_room"), 2e-4)
        from .hard import cases as hard_cases
        black = {c.name for c in hard_cases.CASES if c.black}
        for (_, case), (b, why) in hard_bounds.BLACK_BOUNDS.items():
            self.assertIn(case, black)
            self.assertTrue(b > 0 and why)


def fake_results(tmp):
    tmp = Path(tmp)
    for name in ("ref.png", "a.png", "a.diff.png", "plot.svg"):
        (tmp / name).write_text("x")
    run = {"renderer": "gl_shafts", "label": "planes 100", "params": {}, "status": "ok",
           "tool_seconds": 0.2, "wall_seconds": 0.3, "png": str(tmp / "a.png"),
           "diff_png": str(tmp / "a.diff.png"),
           "metrics": {"rel_rms": 0.03, "mean_rel": 0.01, "psnr": None, "max_abs": 0.1,
                       "scale": 1.0, "bad_values": 0}}
    failed = {"renderer": "gl_shafts", "label": "planes <5> & \"x\"", "params": {},
              "status": "failed", "error": "exit 1 <oops>"}
    return {"mode": "quick", "date": "today", "machine": {"cpu": "cpu", "threads": 2},
            "reference_spp": 512, "lit": 0.01, "elapsed_seconds": 3, "rendered": 2, "cached": 0,
            "renderers": [{"name": "gl_shafts", "label": "gl_shafts", "colour": "#f00",
                           "about": "sweep", "available": True, "note": None, "version": "v"},
                          {"name": "eevee", "label": "EEVEE", "colour": "#0f0", "about": "x",
                           "available": False, "note": "no blender"}],
            "scenes": [{"name": "s", "source": "s.json", "width": 4, "height": 3,
                        "has_medium": True, "runs": [run, failed],
                        "reference": {"label": "ref", "tool_seconds": 1, "png": str(tmp / "ref.png")},
                        "time_to": {"gl_shafts": {"0.01": None, "0.02": None, "0.05": 0.2,
                                                  "best": [0.03, 0.2]}},
                        "plot": str(tmp / "plot.svg")},
                       {"name": "broken", "source": "b.json", "error": "cannot read"}],
            "hard_cases": None}


class ReportTest(unittest.TestCase):
    def test_svg_is_well_formed(self):
        svg = speed_error_svg([{"label": "a & b", "colour": "#123456",
                                "points": [(0.1, 0.05, "x<1>"), (1.0, 0.01, "y"), (2, 0.0, "z"),
                                           (None, 0.1, "untimed")]},
                               {"label": "empty", "colour": "#000", "points": []}], "t <1>")
        root = ET.fromstring(svg)
        self.assertTrue(root.tag.endswith("svg"))
        self.assertIn("Pareto front", svg)
        ET.fromstring(speed_error_svg([], "nothing"))

    def test_html_and_markdown(self):
        with tempfile.TemporaryDirectory() as d:
            results = fake_results(d)
            report.write_html(results, d)
            page = (Path(d) / "index.html").read_text()
            self.assertIn('src="a.png"', page)
            self.assertIn("exit 1 &lt;oops&gt;", page)
            self.assertNotIn("<oops>", page)
            self.assertIn("cannot read", page)
            md = report.summary_markdown(results)
            self.assertIn("| s | 4x3 | gl_shafts | – | – | 200 ms | 3.0 % (200 ms) |", md)

    def test_hard_case_skipped_by_a_renderer_is_reported(self):
        with tempfile.TemporaryDirectory() as d:
            results = fake_results(d)
            why = renderers.Cycles.min_image_why
            results["hard_cases"] = {
                "reference_spp": 16, "renderers": ["gl_shafts"], "failures": [],
                "known_failures": [], "bounds": [],
                "cases": [{"name": "image_1x1", "description": "one pixel", "width": 1,
                           "height": 1, "masked_pixels": 0, "reference": {"seconds": 0.1},
                           "renderings": [],
                           "skipped": [{"renderer": "gl_shafts", "why": why}]}]}
            report.write_html(results, d)
            self.assertIn("Not rendered by", (Path(d) / "index.html").read_text())
            self.assertIn("| image_1x1 | gl_shafts | | not rendered | " + why,
                          report.summary_markdown(results))


    def test_not_exported_is_reported_as_such(self):
        # A renderer whose exporter refuses the scene (the atmosphere for
        # Blender) has a row saying so, with the reason, and no failure.
        with tempfile.TemporaryDirectory() as d:
            results = fake_results(d)
            s = results["scenes"][0]
            s["runs"].append({"renderer": "eevee", "label": "tile 2", "params": {},
                              "status": "not_exported",
                              "error": "the blender exporter does not write <x>"})
            s["not_exported"] = {"eevee": "the blender exporter does not write <x>"}
            report.write_html(results, d)
            page = (Path(d) / "index.html").read_text()
            self.assertIn("not exported: the blender exporter does not write &lt;x&gt;", page)
            md = report.summary_markdown(results)
            self.assertIn("| s | 4x3 | EEVEE | | | | – | not exported: the blender exporter "
                          "does not write <x> |", md)
            self.assertIn("| EEVEE | tile 2 | not exported: the blender", md)


class SweepTest(unittest.TestCase):
    """What the adapters render depends on the scene's medium, and the
    exporter's refusal is "not exported", not a failure."""

    def scene(self, d, medium):
        data = {"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "fov_y_deg": 40,
                           "width": 8, "height": 6}, "lights": []}
        if medium:
            data["medium"] = medium
        return prepare_data("s", data, d, d)

    def test_sweeps_by_medium(self):
        ctx = renderers.Context(ROOT, ROOT / "build", mode="full")
        gl, pov = renderers.GlShafts(), renderers.PovRay()
        with tempfile.TemporaryDirectory() as d:
            atmo = self.scene(d, {"type": "atmosphere"})
            fog = self.scene(d, {"type": "height_fog"})
            box = self.scene(d, {"sigma_s": [1, 1, 1]})
            self.assertEqual((atmo.medium_type, fog.medium_type, box.medium_type),
                             ("atmosphere", "height_fog", "homogeneous"))
            # gl_shafts draws the atmosphere with 1 to 64 planes or spheres.
            planes = [p.get("planes") for _, p in gl.settings(ctx, atmo)]
            self.assertTrue(all(n is None or 1 <= n <= 64 for n in planes))
            self.assertIn(800, [p.get("planes") for _, p in gl.settings(ctx, box)])
            # POV-Ray's density media cost the square of the samples along
            # a ray: no 255 x 4 there.
            for scene in (atmo, fog):
                self.assertTrue(all(p["intervals"] * p["samples"] <= 200
                                    for _, p in pov.settings(ctx, scene)))
            self.assertIn({"intervals": 255, "samples": 4},
                          [p for _, p in pov.settings(ctx, box)])

    def test_atmosphere_features_and_causes(self):
        from . import verdicts
        feats = verdicts.features(json.loads((ROOT / "scenes/sky_sunset.json").read_text()))
        self.assertTrue({"medium:atmosphere", "phase:rayleigh",
                         "phase:cornette_shanks"} <= feats)
        self.assertEqual(verdicts.causes("povray", feats),
                         ["Cornette-Shanks phase exported as HG lobes fitted to it"])
        self.assertIn("Cornette-Shanks phase exported as HG lobes fitted to it",
                      verdicts.causes("cycles", feats))
        fog = verdicts.features(json.loads((ROOT / "scenes/valley_fog.json").read_text()))
        self.assertIn("medium:height_fog", fog)
        self.assertEqual(verdicts.causes("povray", fog), [])
        # The add-on reads height fog, the atmosphere and a homogeneous
        # medium's phase exactly.
        self.assertEqual(verdicts.causes("addon_tracer", feats), [])
        self.assertEqual(verdicts.causes("addon_tracer", fog), [])
        box = {"medium": {"phase": {"type": "nishita_hazy"}}}
        self.assertEqual(verdicts.causes("addon_tracer", verdicts.features(box)), [])

    def test_pages_only_judges_again(self):
        # --pages-only gives an old run today's causes: a POV-Ray series on
        # sky_sunset whose stored note is stale gets the note CAUSES has now.
        from . import validate
        def run(n, e):
            return {"renderer": "povray", "params": {"intervals": n, "samples": 1},
                    "metrics": {"rel_rms": e}}
        entry = {"name": "sky_sunset", "source": "scenes/sky_sunset.json",
                 "runs": [run(25, 0.06), run(50, 0.06)],
                 "verdicts": {"povray": {"kind": "bias", "bias": 0.06, "note": "stale"}}}
        gone = {"name": "gone", "source": "scenes/no_such_scene.json", "runs": [],
                "verdicts": {"povray": {"note": "kept"}}}
        results = {"reference_spp": 1024, "scenes": [entry, gone]}
        self.assertEqual(validate.reclassify(results, ROOT), 1)
        self.assertEqual(entry["verdicts"]["povray"]["note"],
                         "Cornette-Shanks phase exported as HG lobes fitted to it")
        self.assertEqual(gone["verdicts"]["povray"]["note"], "kept")

    def test_command_line_in_summary(self):
        from . import validate
        self.assertEqual(validate.command_line(["--full", "--scenes", "a b.json", "c.json"]),
                         "python3 -m validation.validate --full --scenes 'a b.json' c.json")
        with tempfile.TemporaryDirectory() as d:
            results = fake_results(d)
            results.update(command="python3 -m validation.validate --full", commit="abc123")
            self.assertIn("Command: `python3 -m validation.validate --full`, at abc123.",
                          report.summary_markdown(results))

    def test_scene_modes(self):
        self.assertEqual(mode_scale("scenes/sky_sunset.json", "quick", 0.5), 0.125)
        self.assertEqual(mode_scale("scenes/valley_fog.json", "full", 1.0), 0.2)
        self.assertEqual(mode_scale("scenes/teapot_spot.json", "quick", 0.5), 0.5)

    def test_refusal_is_not_exported(self):
        # The exporter's refusal, and the exported script's for one engine.
        for message, reason in (
                ("scene_export exited with status 2: scene_export: error: s.json:3:9: "
                 "medium.type: the blender exporter does not write a medium of type "
                 "'atmosphere' yet; lmm_tracer renders it",
                 "the blender exporter does not write a medium of type 'atmosphere' yet"),
                ("xvfb-run exited with status 2: scene_export script: error: "
                 "medium.atmosphere: EEVEE does not render a planet's atmosphere (its froxel "
                 "grid is too coarse); render it with --engine cycles",
                 "EEVEE does not render a planet's atmosphere (its froxel grid is too coarse)")):
            e = renderers._refused(RunFailed(message))
            self.assertIsInstance(e, NotExported)
            self.assertEqual(str(e), reason)
        other = RunFailed("blender exited with status 1: segfault")
        self.assertIs(renderers._refused(other), other)
        with tempfile.TemporaryDirectory() as d:
            def render(work, log):
                raise e
            result = execute(RunCache(d), "k" * 64, {"renderer": "cycles"}, render)
            self.assertEqual(result["status"], "not_exported")
            self.assertEqual(RunCache(d).load("k" * 64)["status"], "not_exported")


class SlurmPartsTest(unittest.TestCase):
    """The Slurm executor's parts that need no cluster (slurm_test.py runs
    the executor on one)."""

    def test_array_indices(self):
        self.assertEqual(slurm._indices("3"), [3])
        self.assertEqual(slurm._indices("[4-6%2]"), [4, 5, 6])
        self.assertEqual(slurm._indices("1,3-4"), [1, 3, 4])

    def test_task_that_cannot_see_the_cache_fails_fast(self):
        p = subprocess.run([sys.executable, "-m", "validation.slurm_task", "--probe",
                            "/nonexistent/cache/slurm/sweep/array-0.json"], cwd=ROOT,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.assertEqual(p.returncode, 3)
        self.assertIn("--cache-dir", p.stderr)

    def test_limits_follow_renderer_and_image_size(self):
        class Scene:
            width, height = 160, 120
        big = type("Big", (), {"width": 4000, "height": 3000})
        ctx = renderers.Context(HERE.parent, HERE.parent / "build", mode="quick")
        lmm = renderers.ADAPTERS[0]
        t, mb = lmm.limits(ctx, Scene, {"mode": "reference", "spp": 512})
        # 20 x (2 s + 0.0192 megapixels x 512 spp x 2 s) + 60 s to start.
        self.assertEqual((t, mb % 64), (494, 0))
        t2, mb2 = lmm.limits(ctx, big, {"mode": "reference", "spp": 512})
        self.assertEqual(t2, ctx.timeout + 60)
        self.assertGreater(mb2, mb)
        eevee = renderers.by_name("eevee")[0]
        self.assertGreater(eevee.limits(ctx, Scene, {"tile": 8, "samples": 32,
                                                    "shadow_samples": 16, "taa": 1})[1], mb)

class WarmFrameTest(unittest.TestCase):
    """gl_shafts timed both ways: the bench's table read, the series named."""

    def test_bench_table_and_labels(self):
        text = ("rendering...\n"
                "| scene | size | planes | ms/frame: best (median) | CPU ms/frame | first frame "
                "ms (with context) | backend: GL_RENDERER (GL_VENDOR) |\n"
                "|---|---|---|---|---|---|---|\n"
                "| teapot_spot.json | 160x120 | 25 | 36.0 (51.9) | 18.1 | 1630.1 | egl: "
                "llvmpipe (LLVM 15.0.6, 256 bits) (Mesa/X.org) |\n")
        self.assertEqual(renderers._bench_frame_ms(text), (36.0, 51.9))
        self.assertIsNone(renderers._bench_frame_ms("| a |\n|---|\n| 1 |\n"))
        rix = {"gl_shafts": {"label": "gl_shafts"}, "cycles": {"label": "Cycles"}}
        keys = ["gl_shafts:warm", "gl_shafts", "cycles"]
        self.assertEqual([report.series_label(rix, k, keys) for k in keys],
                         ["gl_shafts, warm frame", "gl_shafts, first image", "Cycles"])


class ProgressTest(unittest.TestCase):
    """The progress messages: counts, the case's name, the time left."""

    def test_counts_names_and_time_left(self):
        class Adapter:
            name, startup_seconds, seconds_per_megapixel = "slow", 10.0, 0.0

            def work(self, params):
                return 1.0

        class Scene:
            width = height = 10

        runs = [Run("k%d" % i, "v", {"scene": "case%d" % i}, Adapter(), Scene, {})
                for i in range(3)]

        class Cache:
            def load(self, key):
                # A cached run that took half the cost model's 10 s.
                return {"status": "ok", "wall_seconds": 5.0} if key == "k0" else None

        clock = [0.0]

        class Inner:
            name = "local"

            def run(self, run, say=None):
                say("rendering slow: x")
                clock[0] += 5.0  # half the cost model's 10 s
                return {"status": "ok"}

        ex = ProgressExecutor(Inner(), Cache(), runs, clock=lambda: clock[0])
        self.assertEqual((ex.total, len(ex.done)), (3, 1))
        # The cached run calibrates: two runs of 10 s guessed at 5 s each.
        self.assertEqual(ex.seconds_left(), 10.0)
        said = []
        ex.run(runs[1], say=said.append)
        self.assertEqual(said, ["[2/3 renderings, 10 s left] case1: rendering slow: x"])
        # This run took half the estimate too: the last one is guessed at 5 s.
        self.assertEqual(ex.seconds_left(), 5.0)
        self.assertEqual(fmt_left(3725), "1 h 02 min")
        self.assertEqual(fmt_left(200), "3 min 20 s")


class PovFramesTest(unittest.TestCase):
    """pov_frames: the frames' signed sum as the .ini's Frame_Signs says (a
    lobe of negative weight is rendered with |w| and subtracted); oiiotool
    makes constant half-float frames (OpenImageIO, as POV-Ray writes)."""

    @staticmethod
    def _frame(path, rgb):
        subprocess.run(["oiiotool", "--create", "2x2", "3",
                        "--fill:color=%g,%g,%g" % rgb, "0,0,2,2", "-d", "half",
                        "-o", str(path)], check=True, capture_output=True)

    @staticmethod
    def _colour(path):
        out = subprocess.run(["oiiotool", str(path), "--printstats"], check=True,
                             capture_output=True, text=True).stdout
        line = next(l for l in out.splitlines() if "Stats Avg:" in l)
        return [float(v) for v in line.split(":")[1].split()[:3]]

    def test_signed_sum(self):
        with tempfile.TemporaryDirectory() as tmp:
            work = Path(tmp)
            for i, rgb in enumerate([(1, 2, 3), (0.5, 0.5, 0.5), (0.25, 0, 1)]):
                self._frame(work / ("scene%d.exr" % (i + 1)), rgb)
            ini = work / "scene.ini"
            ini.write_text("Input_File_Name=scene.pov\n; Frame_Signs=+ - +\n"
                           "Initial_Frame=1\nFinal_Frame=3\n")
            self.assertEqual(self._colour(renderers.pov_frames(work)), [0.75, 1.5, 3.5])
            ini.write_text("Initial_Frame=1\nFinal_Frame=3\n")  # no signs: all added
            self.assertEqual(self._colour(renderers.pov_frames(work)), [1.75, 2.5, 4.5])
            ini.write_text("; Frame_Signs=+ -\n")  # signs that do not match the frames
            with self.assertRaises(RunFailed):
                renderers.pov_frames(work)


class AtmoPhaseBiasTest(unittest.TestCase):
    """atmo_phase_bias's pieces: the phases are normalised (Simpson over
    cos), Rayleigh is Cornette-Shanks at g = 0, and a pixel's phase angle
    follows core/sh_camera.c (the centre pixel of an odd image looks along
    the view; looking into the light, cos = 1 there)."""

    def test_phases(self):
        n = 4000
        for f in (atmo_phase_bias.rayleigh, lambda c: atmo_phase_bias.hg(0.6, c),
                  lambda c: atmo_phase_bias.cornette_shanks(0.5, c)):
            s = f(-1.0) + f(1.0) + sum((4 if j % 2 else 2) * f(-1.0 + 2.0 * j / n)
                                       for j in range(1, n))
            self.assertAlmostEqual(2 * math.pi * s * (2.0 / n) / 3.0, 1.0, places=6)
        for c in (-1.0, 0.3, 1.0):
            self.assertAlmostEqual(atmo_phase_bias.rayleigh(c),
                                   atmo_phase_bias.cornette_shanks(0.0, c), places=12)

    def test_pixel_mu(self):
        cam = {"position": [0, 0, 0], "look_at": [1, 0, 0], "fov_y_deg": 60}
        mu = atmo_phase_bias.pixel_mu(cam, [-1, 0, 0], 5, 3)
        self.assertAlmostEqual(mu[(2, 1)], 1.0, places=12)
        # Half the field of view up (the top row's centre is 2/3 of it).
        tan_top = math.tan(math.radians(30)) * 2.0 / 3.0
        self.assertAlmostEqual(mu[(2, 0)], 1.0 / math.sqrt(1 + tan_top ** 2), places=12)
        self.assertAlmostEqual(mu[(0, 1)], mu[(4, 1)], places=12)


if __name__ == "__main__":
    unittest.main()
