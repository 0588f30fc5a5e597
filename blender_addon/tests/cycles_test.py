"""The tracer's F12 (reference mode) agrees with Cycles on the same Blender
scene, a spot and a caster in a box of Henyey-Greenstein medium (g = 0.4,
with absorption), within Cycles' own noise as measured in the same run.

Threshold: Cycles is rendered twice, seeds 0 and 1, at CYCLES_SPP; the
relative RMS over the lit pixels between the two, n, is the measured noise
(each render's own is about n / sqrt 2). Ours at TRACER_SPP is nearly
noise-free, so an unbiased F12 differs from a Cycles render by about
n / sqrt 2 = 0.71 n; the check allows 1.5 n (a bias of about 1.3 n on top
of the noise fails it). Cycles renders single scattering with direct light
only here (volume and diffuse bounces 0, the rest 5, as scene_export's
Cycles script sets it: with no bounces at all Cycles lights no surface), one sample position per pixel centre as our renderers take."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import addon_test_lib as t  # noqa: E402

t.install()
t.require("shafts", "convert")
from scenes import spot_in_volume_box  # noqa: E402

CYCLES_SPP, TRACER_SPP, FACTOR = 512, 256, 1.5
out = t.SCRATCH
scene = spot_in_volume_box()
# The floor lies in the volume box's bottom face there; Cycles cannot tell
# which of two coincident surfaces a ray meets first (its floor came out
# black), so the floor goes 2 cm down, out of the box.
scene.objects["Floor"].location.z = -0.02
# Edges of the caster and its shadow fell on rows of pixel centres, where
# Cycles' tiny filter jitter splits a pixel that our centre sample does not:
# the camera moves off them.
scene.camera.location = (0.03, -8, 3.05)
scene.render.engine = "SHAFTS_TRACER"
scene.shafts_tracer.spp = TRACER_SPP
t.check(t.f12(scene, out / "tracer.exr") == {'FINISHED'}, "the tracer's F12")

scene.render.engine = "CYCLES"
c = scene.cycles
c.device, c.samples, c.use_adaptive_sampling, c.use_denoising = "CPU", CYCLES_SPP, False, False
c.max_bounces, c.diffuse_bounces, c.glossy_bounces, c.transmission_bounces = 5, 0, 5, 5
c.volume_bounces, c.caustics_reflective, c.caustics_refractive = 0, False, False
c.sample_clamp_direct = c.sample_clamp_indirect = c.light_sampling_threshold = 0.0
c.pixel_filter_type, c.filter_width = "GAUSSIAN", 0.01
for seed in (0, 1):
    c.seed = seed
    t.check(t.f12(scene, out / ("cycles%d.exr" % seed)) == {'FINISHED'}, "Cycles, seed %d" % seed)
noise = t.compare(str(out / "cycles0.exr"), str(out / "cycles1.exr"))["rel_rms"]
d = t.compare(str(out / "cycles0.exr"), str(out / "tracer.exr"), diff=str(out / "diff.png"))
t.check(d["lit_pixels"] > 100, "the scene is lit (%d pixels)" % d["lit_pixels"])
t.check(d["rel_rms"] <= FACTOR * noise,
        "the tracer agrees with Cycles: rel RMS %.4f <= %.1f x Cycles' noise %.4f (mean rel %.4f)"
        % (d["rel_rms"], FACTOR, noise, d["mean_rel"]))
sums = {name: t.exr_sum(out / (name + ".exr")) for name in ("tracer", "cycles0", "cycles1")}
print("image sums (radiance over all pixels): tracer %.4g, Cycles %.4g and %.4g: ratio %.4f"
      % (sums["tracer"], sums["cycles0"], sums["cycles1"],
         2 * sums["tracer"] / (sums["cycles0"] + sums["cycles1"])))
t.finish()
