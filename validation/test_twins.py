#!/usr/bin/env python3
"""Unit tests of the scenes' twins (twins.py) and of the bias-or-noise
verdicts (verdicts.py); no renderer needed. Run from the source
tree: python3 -m validation.test_twins."""

import json
import math
import tempfile
import unittest
from pathlib import Path

from . import report, verdicts
from .scenes import prepare_file
from .twins import make_twin, mean_cosine, prepare_twin, twin_phase

HERE = Path(__file__).resolve().parent
SCENES = HERE.parent / "scenes"


def numeric_mean_cosine(shape, n=200000):
    """The mean cosine of a phase shape p(mu), by the midpoint rule in mu."""
    num = den = 0.0
    for i in range(n):
        mu = -1 + (i + 0.5) * 2.0 / n
        p = shape(mu)
        num += p * mu
        den += p
    return num / den


class TwinsTest(unittest.TestCase):
    def test_mean_cosines(self):
        # The closed forms against the shapes of docs/scene-format.md.
        hazy = numeric_mean_cosine(lambda mu: 1 + 9 * ((1 + mu) / 2) ** 8)
        murky = numeric_mean_cosine(lambda mu: 1 + 50 * ((1 + mu) / 2) ** 32)
        self.assertAlmostEqual(mean_cosine({"type": "nishita_hazy"}), hazy, places=6)
        self.assertAlmostEqual(mean_cosine({"type": "nishita_hazy"}), 0.4, places=12)
        self.assertAlmostEqual(mean_cosine({"type": "nishita_murky"}), murky, places=6)
        self.assertAlmostEqual(mean_cosine({"type": "nishita_murky"}), 800 / 1411, places=12)
        self.assertEqual(mean_cosine({"type": "rayleigh"}), 0.0)
        self.assertEqual(mean_cosine({"type": "henyey_greenstein", "g": -0.3}), -0.3)

    def test_phase_stand_ins(self):
        self.assertEqual(twin_phase({"type": "nishita_hazy"})[0],
                         {"type": "henyey_greenstein", "g": 0.4})
        self.assertEqual(twin_phase({"type": "rayleigh"})[0], {"type": "isotropic"})
        self.assertIsNone(twin_phase({"type": "isotropic"}))
        self.assertIsNone(twin_phase({"type": "henyey_greenstein", "g": 0.7}))

    def test_canonical_twins(self):
        # Every canonical scene with a medium uses a phase the peers
        # approximate, so every one has an HG twin; Phong goes where it is.
        for path in sorted(SCENES.glob("*.json")):
            data = json.loads(path.read_text())
            made = make_twin(path.stem, data)
            if data.get("medium", {}).get("type") == "atmosphere":
                # Its phase is the Rayleigh and Mie mixture, not a key the
                # twin replaces (scenes/README.md): no twin yet.
                self.assertIsNone(made, path.name)
                continue
            phong = [n for n, m in data["materials"].items() if "specular" in m]
            if "medium" not in data and not phong:
                self.assertIsNone(made, path.name)
                continue
            name, twin, changes = made
            if "medium" in data:
                self.assertIn("-hg", name)
                self.assertEqual(twin["medium"]["phase"]["type"], "henyey_greenstein")
                self.assertEqual({k: v for k, v in twin["medium"].items() if k != "phase"},
                                 {k: v for k, v in data["medium"].items() if k != "phase"})
            self.assertEqual("-lambert" in name, bool(phong), path.name)
            for n, m in twin["materials"].items():
                self.assertNotIn("specular", m)
                self.assertNotIn("shininess", m)
                self.assertEqual(m.get("diffuse"), data["materials"][n].get("diffuse"))
                self.assertEqual(m.get("transmit"), data["materials"][n].get("transmit"))
            for key in ("camera", "lights", "shapes"):
                self.assertEqual(twin[key], data[key])
            self.assertTrue(changes)

    def test_prepared_twin(self):
        with tempfile.TemporaryDirectory() as d:
            path = SCENES / "teapot_spot.json"
            scene, changes, data = prepare_twin(path, d, scale=0.25)
            own = prepare_file(path, d, scale=0.25)
            self.assertEqual(scene.name, "teapot_spot-hg-lambert")
            self.assertNotEqual(scene.key, own.key)
            self.assertEqual((scene.width, scene.height), (own.width, own.height))
            derived = json.loads(scene.path.read_text())
            self.assertEqual(derived["medium"]["phase"]["g"], 0.4)
            # Its mesh is named relatively, a copy in its own directory.
            meshes = [s["file"] for s in derived["shapes"] if "file" in s]
            self.assertTrue(meshes and all(not Path(m).is_absolute() and
                                           (scene.path.parent / m).is_file()
                                           for m in meshes))
            self.assertEqual(data["medium"]["phase"]["type"], "nishita_hazy")
            self.assertIsNone(prepare_twin(Path(d) / "missing.json", d))


def run(renderer, params, err):
    return {"renderer": renderer, "params": params, "metrics": {"rel_rms": err},
            "status": "ok", "label": "x", "tool_seconds": 1.0}


class VerdictsTest(unittest.TestCase):
    def test_split(self):
        # Pure noise: quadrupling the samples halves the error.
        bias, noise = verdicts.split(0.2, 0.1, 4)
        self.assertAlmostEqual(bias, 0.0)
        self.assertAlmostEqual(noise, 0.1)
        # A floor: b = 0.1, c / n2 = 0.01^2 at n2.
        e2 = math.hypot(0.1, 0.01)
        e1 = math.hypot(0.1, 0.02)
        bias, noise = verdicts.split(e1, e2, 4)
        self.assertAlmostEqual(bias, 0.1, places=9)
        self.assertAlmostEqual(noise, 0.01, places=9)
        # An error that grew: all bias.
        self.assertEqual(verdicts.split(0.10, 0.11, 4), (0.11, 0.0))

    def test_monte_carlo_series(self):
        # The full run's Cycles figures (validation/summary.md at 76a206e).
        mountains = [run("cycles", {"samples": n}, e)
                     for n, e in ((64, 0.19), (256, 0.19), (1024, 0.19))]
        v = verdicts.classify_runs("cycles", mountains)
        self.assertEqual(v["kind"], "bias")
        self.assertAlmostEqual(v["bias"], 0.19)
        self.assertFalse(v["falls"])
        stage = [run("cycles", {"samples": 256}, 0.36), run("cycles", {"samples": 1024}, 0.21)]
        v = verdicts.classify_runs("cycles", stage)
        self.assertEqual(v["kind"], "noise")
        self.assertAlmostEqual(v["noise"], 0.169, places=3)
        self.assertAlmostEqual(v["bias"], 0.125, places=3)
        # lmm_tracer's series is its reference mode; whitted is left out.
        lmm = [run("lmm_tracer", {"mode": "reference", "spp": 128}, 0.002),
               run("lmm_tracer", {"mode": "reference", "spp": 256}, 0.00099),
               run("lmm_tracer", {"mode": "whitted", "spp": 16}, 0.016)]
        v = verdicts.classify_runs("lmm_tracer", lmm)
        self.assertEqual((v["kind"], v["bias"]), ("noise", 0.0))
        self.assertEqual(verdicts.classify_runs(
            "lmm_tracer", [run("lmm_tracer", {"mode": "reference", "spp": 1}, 0.0)])["kind"],
            "exact")

    def test_deterministic_series(self):
        falling = [run("gl_shafts", {"planes": 400, "xi": "exact"}, 0.0006),
                   run("gl_shafts", {"planes": 800, "xi": "exact"}, 0.0003),
                   run("gl_shafts", {"planes": 800, "xi": "exact", "jitter": True}, 0.0001),
                   run("gl_shafts", {"planes": 100, "xi": "lattice"}, 0.3)]
        v = verdicts.classify_runs("gl_shafts", falling)
        self.assertEqual((v["kind"], v["falls"], v["bias"]), ("bias", True, 0.0003))
        floor = [run("gl_shafts", {"planes": 400, "xi": "exact"}, 0.018),
                 run("gl_shafts", {"planes": 800, "xi": "exact"}, 0.018)]
        self.assertFalse(verdicts.classify_runs("gl_shafts", floor)["falls"])
        single = verdicts.classify_runs("gl_shafts", [run("gl_shafts", {}, 0.27)])
        self.assertEqual((single["kind"], single["bias"], single["falls"]), ("bias", 0.27, None))
        self.assertIsNone(verdicts.classify_runs("cycles", []))
        sweep = verdicts.classify_runs("addon_sweep", [run("addon_sweep", {}, 0.02)])
        self.assertEqual((sweep["kind"], sweep["bias"]), ("bias", 0.02))
        eevee = [run("eevee", {"tile": 16, "samples": 16, "taa": 1}, 0.45),
                 run("eevee", {"tile": 2, "samples": 128, "taa": 8}, 0.45)]
        v = verdicts.classify_runs("eevee", eevee)
        self.assertEqual((v["kind"], v["falls"]), ("bias", False))

    def test_causes_and_notes(self):
        data = json.loads((SCENES / "teapot_spot.json").read_text())
        feats = verdicts.features(data)
        self.assertTrue({"medium", "phase:nishita_hazy", "phong", "shadows",
                         "light_in_view"} <= feats)
        self.assertNotIn("several_lights", feats)
        entry = {"runs": [run("cycles", {"samples": 256}, 0.10),
                          run("cycles", {"samples": 1024}, 0.11),
                          run("gl_shafts", {"planes": 400, "xi": "exact"}, 0.0006),
                          run("gl_shafts", {"planes": 800, "xi": "exact"}, 0.0003)]}
        twin = {"verdicts": {"cycles": {"kind": "noise", "bias": 0.0, "noise": 0.004,
                                        "error": 0.004}}}
        out = verdicts.classify(entry, data, twin)
        self.assertIn("Nishita hazy", out["cycles"]["note"])
        self.assertIn("Glossy", out["cycles"]["note"])
        self.assertIn("on the twin: noise", out["cycles"]["note"])
        self.assertTrue(verdicts.text(out["cycles"]).startswith("bias 11 %: "))
        self.assertIn("discretisation", out["gl_shafts"]["note"])
        # A scene without the approximated features leaves Cycles' bias
        # unexplained, and says so.
        plain = {"camera": data["camera"], "lights": [], "materials": {}}
        self.assertEqual(verdicts.classify(entry, plain)["cycles"]["note"],
                         "cause not identified")
        # With surfaces and nothing approximated: the edge pixels.
        lambert = dict(plain, lights=data["lights"], shapes=data["shapes"])
        self.assertEqual(verdicts.classify(entry, lambert)["cycles"]["note"],
                         verdicts.FALLBACK["cycles"])

    def test_reference_noise_and_least_bias(self):
        # mountains_sun in the full run of 76a206e: lmm_tracer's reference
        # mode at 128 and 256 spp is 0.2% and 0.099% from the reference at
        # 4096 (stratified: the error falls as 1/spp), so the reference's
        # own noise is 0.099% / 16; gl_shafts' 0.054% floor is its own.
        data = json.loads((SCENES / "mountains_sun.json").read_text())
        lmm = [run("lmm_tracer", {"mode": "reference", "spp": 128}, 0.002),
               run("lmm_tracer", {"mode": "reference", "spp": 256}, 0.00099)]
        entry = {"runs": lmm + [run("gl_shafts", {"planes": 400, "xi": "exact"}, 0.00063),
                                run("gl_shafts", {"planes": 800, "xi": "exact"}, 0.00054)]}
        self.assertAlmostEqual(verdicts.reference_noise(entry, 4096), 0.00099 / 16, places=6)
        self.assertIsNone(verdicts.reference_noise({"runs": []}, 4096))
        v = verdicts.classify(entry, data, ref_spp=4096)["gl_shafts"]
        self.assertEqual(v["note"], "shadow-map edges")
        # Plain Monte Carlo (or a single run): 1/sqrt(spp), the larger.
        lmm[0]["metrics"]["rel_rms"] = 0.0014
        self.assertAlmostEqual(verdicts.reference_noise(entry, 4096), 0.00099 / 4, places=6)
        lmm[1]["metrics"]["rel_rms"] = 0.0012
        v = verdicts.classify(entry, data, ref_spp=4096)["gl_shafts"]
        self.assertTrue(v["note"].startswith("the reference's own noise"))
        # POV-Ray's total internal reflection explains 2.4%, not 0.02%.
        self.assertEqual(verdicts.causes("povray", {"transmit"}, 0.024),
                         ["total internal reflection in the glass"])
        self.assertEqual(verdicts.causes("povray", {"transmit"}, 0.0002), [])

    def test_light_in_view_judged_away_from_it(self):
        # Cycles on teapot_spot's twin at 80x60 (quick): fireflies next to
        # the light keep the whole image's error from falling as noise
        # does (98% to 67%); away from the light it does (76% to 24%).
        data = json.loads((SCENES / "teapot_spot.json").read_text())
        runs = [run("cycles", {"samples": 4}, 0.98), run("cycles", {"samples": 16}, 0.67)]
        runs[0]["metrics_masked"] = {"rel_rms": 0.76}
        runs[1]["metrics_masked"] = {"rel_rms": 0.24}
        self.assertEqual(verdicts.classify_runs("cycles", runs)["kind"], "bias")
        v = verdicts.classify({"runs": runs}, data)["cycles"]
        self.assertEqual((v["kind"], v["away_from_lights"]), ("noise", True))

    def test_summary_says_the_verdict(self):
        entry = {"name": "s", "source": "s.json", "width": 4, "height": 3,
                 "runs": [run("cycles", {"samples": 4}, 0.2)],
                 "time_to": {"cycles": {"0.01": None, "0.02": None, "0.05": None,
                                        "best": [0.2, 1.0]}},
                 "reference": {"label": "ref", "tool_seconds": 1.0, "png": "r.png"},
                 "twin": {"name": "s-hg", "changes": ["nishita_hazy phase as HG"],
                          "shift": 0.1},
                 "plot": "p.svg",
                 "verdicts": {"cycles": {"kind": "bias", "bias": 0.2, "note": "a | b"}}}
        results = {"mode": "quick", "date": "now", "machine": {}, "reference_spp": 16,
                   "lit": 0.01, "scenes": [entry], "hard_cases": None,
                   "renderers": [{"name": "cycles", "label": "Cycles", "available": True,
                                  "colour": "#000", "about": ""}]}
        md = report.summary_markdown(results)
        self.assertIn("| bias 20 %: a / b |", md)
        self.assertIn("Twin: s-hg: nishita_hazy phase as HG. Its reference differs", md)


if __name__ == "__main__":
    unittest.main()
