"""The exported script's passes per colour channel (blender_build.py,
render_image): a ray-marched medium whose coefficients differ between
channels is rendered once per channel with grey coefficients and the
passes composed (docs/scene_export.md, "The atmosphere in Cycles").

    blender -b --factory-startup --python test_channels.py -- BUILD_DIR

Checks: compose_channels takes channel c of pass c exactly (32-bit float
OpenEXR, no colour conversion, values from 1e-6 to 1e4); which materials
call for passes (a chromatic heterogeneous volume does; a grey one, a
homogeneous one and a surface do not) and that set_channel makes them grey
and restores them; and the script itself on height_fog_sun at 8x6, 2
samples: three passes by default, one with --one-pass.
"""
import importlib.util
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy

import harness as H

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
spec = importlib.util.spec_from_file_location(
    "blender_build", os.path.join(ROOT, "blender_addon", "shafts_blender", "convert",
                                  "blender_build.py"))
bb = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bb)

W, H_ = 5, 3


def value(c, k, pixel):
    """A distinct value for channel k of pixel `pixel` of pass c."""
    return (1e-6, 0.37, 1e4)[c] * (1 + pixel) * (1 + 0.1 * k)


def read(path):
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"
    px = list(img.pixels)
    size, channels = tuple(img.size), img.channels
    bpy.data.images.remove(img)
    return size, channels, px


def test_compose(work):
    scene = bpy.context.scene
    bb.setup_render(scene, {"render": {"width": W, "height": H_}},
                    {"engine": "cycles", "samples": 1, "seed": 0}, None)
    passes = []
    for c in range(3):
        img = bpy.data.images.new("pass%d" % c, W, H_, alpha=True, float_buffer=True)
        img.colorspace_settings.name = "Non-Color"
        img.pixels.foreach_set([value(c, k, p) if k < 3 else 1.0
                                for p in range(W * H_) for k in range(4)])
        path = os.path.join(work, "pass%d.exr" % c)
        img.save_render(path, scene=scene)
        bpy.data.images.remove(img)
        passes.append(path)
    out = bb.compose_channels(passes, os.path.join(work, "composed.exr"), scene)
    size, channels, px = read(out)
    H.check("composed size", size == (W, H_), str(size))
    want = [value(k, k, p) if k < 3 else 1.0 for p in range(W * H_) for k in range(channels)]
    H.near("channel c of pass c", px, want, tol=1e-6)
    info = subprocess.run(["oiiotool", "--info", "-v", out], capture_output=True,
                          text=True).stdout
    H.check("32-bit float OpenEXR", "float" in info and "half" not in info, info.strip())
    try:
        bb.compose_channels(passes[:2] + [os.path.join(work, "missing.exr")],
                            os.path.join(work, "bad.exr"), scene)
        H.check("a missing pass raises", False)
    except RuntimeError:
        H.check("a missing pass raises", not os.path.exists(os.path.join(work, "bad.exr")))


def volume_object(name, colour, homogeneous, volume=True):
    mat, tree, out = bb.new_material(name)
    mat.cycles.homogeneous_volume = homogeneous
    n = bb.node(tree, "ShaderNodeVolumeScatter" if volume else "ShaderNodeBsdfDiffuse",
                Color=colour)
    tree.links.new(n.outputs[0], out.inputs["Volume" if volume else "Surface"])
    mesh = bb.box_mesh((0, 0, 0), (1, 1, 1))
    mesh.materials.append(mat)
    return bb.new_object(name, mesh, bpy.context.scene.collection), n


def test_inputs():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    volume_object("grey fog", (0.5, 0.5, 0.5, 1), False)
    volume_object("chromatic box", (0.2, 0.4, 1.0, 1), True)
    volume_object("chromatic surface", (0.2, 0.4, 1.0, 1), False, volume=False)
    H.check("grey, homogeneous or surface colours: one pass",
            bb.chromatic_marched_inputs(scene) == [])
    _, n = volume_object("chromatic fog", (0.2, 0.4, 1.0, 1), False)
    inputs = bb.chromatic_marched_inputs(scene)
    H.check("a chromatic ray-marched medium: passes", len(inputs) == 2, str(len(inputs)))
    bb.set_channel(inputs, 1)
    H.near("pass 1 is grey at the green value", tuple(n.inputs["Color"].default_value),
           (0.4, 0.4, 0.4, 1))
    bb.set_channel(inputs, None)
    H.near("restored", tuple(n.inputs["Color"].default_value), (0.2, 0.4, 1.0, 1))


def test_script(work):
    build = H.build_dir()
    scene = H.scene_copy(os.path.join(ROOT, "scene_export", "testdata", "height_fog_sun.json"),
                         work, (8, 6))
    py = os.path.join(work, "fog.py")
    subprocess.run([os.path.join(build, "scene_export", "scene_export"), scene,
                    "--to", "blender", "-o", py], check=True, capture_output=True)
    for extra, passes in (([], 3), (["--one-pass"], 0)):
        out = os.path.join(work, "fog%d.exr" % passes)
        r = subprocess.run([bpy.app.binary_path, "-b", "--factory-startup", "-noaudio", "-P",
                            py, "--", "--engine", "cycles", "--out", out, "--samples", "2"]
                           + extra, capture_output=True, text=True)
        said = r.stdout.count("scene_export script: pass ")
        H.check("script %s: exit 0, %d passes, image written" % (extra, passes),
                r.returncode == 0 and said == passes and os.path.exists(out),
                "exit %d, %d passes said; %s" % (r.returncode, said, r.stderr.strip()[-300:]))
        H.check("no temporary file left beside the image (%s)" % extra,
                [f for f in os.listdir(work) if f.startswith(".")] == [])


with tempfile.TemporaryDirectory(prefix="test_channels_") as d:
    test_compose(d)
    test_inputs()
    test_script(d)
H.finish()
