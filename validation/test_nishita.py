"""Unit tests of validation/nishita.py's pure parts (no rendering): the
frames, the single-precision solid angle, the scenes it writes.

  python3 -m validation.test_nishita
"""

import math
import unittest

from . import bench_sky, nishita


class Frames(unittest.TestCase):
    def test_sun_is_blenders(self):
        # Blender's Nishita sun at rotation 0: (0, cos e, sin e), Z up.
        for e in (2.0, 10.0, 60.0):
            b = nishita.to_blender(nishita.direction(e, 0.0))
            r = math.radians(e)
            for got, want in zip(b, (0.0, math.cos(r), math.sin(r))):
                self.assertAlmostEqual(got, want, places=12)

    def test_probes(self):
        z = nishita.probe_direction(nishita.PROBES[0], 10.0)
        self.assertAlmostEqual(z[1], 1.0, places=12)
        near = nishita.probe_direction(nishita.PROBES[1], 10.0)
        self.assertAlmostEqual(math.degrees(math.asin(near[1])), 15.0, places=9)
        side = nishita.probe_direction(nishita.PROBES[3], 10.0)
        self.assertAlmostEqual(side[2], 0.0, places=12)  # 90 degrees from the sun


class SolidAngle(unittest.TestCase):
    def test_single_precision(self):
        exact = nishita.exact_solid_angle(0.545)
        self.assertAlmostEqual(exact, 2 * math.pi * (1 - math.cos(math.radians(0.2725))),
                               delta=1e-15)
        f = nishita.blender_solid_angle(0.545)
        # Within float's few digits of 1 - cos, and not the exact value.
        self.assertLess(abs(f / exact - 1), 0.01)


class Scene(unittest.TestCase):
    def test_contract_keys(self):
        s = nishita.sky_scene(10.0, [1, 2, 3], nishita.BRUNETON, [0, 1, 0], 1.0, 5, 5, 16)
        m = s["medium"]
        self.assertEqual(m["type"], "atmosphere")
        self.assertEqual(set(m), {"type", "center", "ground_radius", "top_radius",
                                  "rayleigh", "mie", "ozone"})
        self.assertEqual(s["camera"]["up"], [0.0, 0.0, -1.0])  # looking up
        light = s["lights"][0]
        self.assertAlmostEqual(light["direction"][1], -math.sin(math.radians(10)), places=12)
        self.assertEqual(light["angular_diameter_deg"], nishita.SUN_SIZE_DEG)

    def test_blender_constants(self):
        c = nishita.CONSTANTS["blender_rgb"]
        # Rayleigh falls with wavelength; Mie is 2e-5 per metre, 0.02 per km.
        r = c["rayleigh"]["sigma_s"]
        self.assertTrue(r[0] < r[1] < r[2])
        self.assertAlmostEqual(c["mie"]["sigma_s"][0], 0.02, places=12)
        self.assertAlmostEqual(c["mie"]["sigma_a"][0], 0.0022, places=12)


class BenchSkyView(unittest.TestCase):
    """validation/bench_sky.py's Nishita view of a scene."""

    def scene(self, eye_height, elevation=10.0):
        sun = nishita.direction(elevation, 30.0)
        return {"camera": {"position": [0, eye_height, 0], "look_at": [0, eye_height, -1],
                           "fov_y_deg": 40, "width": 64, "height": 48},
                "medium": {"type": "atmosphere", "center": [0, -6360, 0],
                           "ground_radius": 6360, "top_radius": 6420},
                "lights": [{"type": "directional", "direction": [-c for c in sun],
                            "irradiance": [1, 2, 3]}]}

    def test_frame(self):
        view, irradiance = bench_sky.blender_sky_view(self.scene(0.002))
        self.assertAlmostEqual(view["elevation_deg"], 10.0, places=9)
        self.assertAlmostEqual(view["altitude_m"], 2.0, places=6)
        # The camera looks at azimuth -30 degrees from the sun's, which
        # nishita.py's frame (the sun at azimuth 0, Blender's +Y) maps so.
        want = nishita.to_blender(nishita.direction(0.0, -30.0))
        for got, w in zip(view["dir"], want):
            self.assertAlmostEqual(got, w, places=9)
        self.assertEqual(irradiance, [1, 2, 3])
        self.assertFalse(view["sun_disc"])  # the scene's sun has no disk

    def test_limits(self):
        with self.assertRaises(bench_sky.Skip):
            bench_sky.blender_sky_view(self.scene(100.0))  # above 60 km
        s = self.scene(0.002)
        s["medium"] = {"type": "homogeneous"}
        with self.assertRaises(bench_sky.Skip):
            bench_sky.blender_sky_view(s)


class BenchTable(unittest.TestCase):
    """bench_sky's table: the truth's noise, errors net of it, the time at
    gl_shafts' error and issue 12's verdict."""

    class Ctx:
        spp, ref_spp = 4, 16

    class Scene:
        width, height = 640, 480

    def rows(self, gl_secs=0.030):
        return [("gl_shafts", "defaults", gl_secs, 0.028),
                ("reference", "4 spp", 10.0, 0.05),
                ("pov", "draft", 5.0, 0.13)]

    def test_truth_noise(self):
        # e_ref^2 = s^2 (1/4 + 1/16): s^2 = 0.008, the truth's s^2 / 16.
        n2 = bench_sky.truth_noise2(self.Ctx, self.rows())
        self.assertAlmostEqual(n2, 0.0005, places=12)
        self.assertAlmostEqual(bench_sky.net(0.028, n2), math.sqrt(0.000284), places=12)
        self.assertEqual(bench_sky.net(0.01, n2), 0.0)  # below the truth's noise
        self.assertIsNone(bench_sky.truth_noise2(self.Ctx, self.rows()[:1]))

    def test_table(self):
        text = bench_sky.table(self.Ctx, "sky", self.Scene, self.rows())
        # The reference at gl_shafts' error: 10 s x (0.002 / 0.000284).
        self.assertIn("%.4g (est.)" % (10.0 * 0.002 / 0.000284), text)
        self.assertIn("| pov | draft |", text)
        self.assertIn("n/a: not noise", text)
        self.assertIn(": met", text)
        slow = bench_sky.table(self.Ctx, "sky", self.Scene, self.rows(0.060))
        self.assertIn("NOT met", slow)
        quiet = [("gl_shafts", "defaults", 0.03, 0.01)] + self.rows()[1:]
        text = bench_sky.table(self.Ctx, "sky", self.Scene, quiet)
        # gl_shafts within the truth's noise (s^2 / M = 0.0005): the
        # reference's time to that noise, 10 s x 0.002 / 0.0005, a lower
        # bound; a POV-Ray within it too is at gl_shafts' error in its time.
        self.assertIn("> 40 (est., to the truth's noise: gl_shafts' error is within it)", text)
        exact = quiet[:2] + [("pov", "draft", 5.0, 0.015)]
        self.assertIn("its own (its error at most gl_shafts'",
                      bench_sky.table(self.Ctx, "sky", self.Scene, exact))

    def test_size(self):
        class Small:
            width, height = 64, 48
        text = bench_sky.table(self.Ctx, "sky", Small, self.rows())
        self.assertIn("not judged (not 640x480)", text)


if __name__ == "__main__":
    unittest.main()
