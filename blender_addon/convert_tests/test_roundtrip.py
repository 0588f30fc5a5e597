"""Scene -> Blender -> scene: a scene file imported with the add-on's
importer (the C writer of scene_export --to blender, through libshafts.so,
and the builder its script runs) and exported again gives the same scene:
the same camera, lights, medium and materials (value by value), the same
image from the reference renderer (lmm_tracer, within the bound below),
and no warning (every feature of this scene converts exactly both ways).
Also File > Export's operator and tools/blend2shafts: whole files or none.

    blender -b --factory-startup --python test_roundtrip.py -- BUILD_DIR
"""
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy
import numpy as np

import harness as H
import artist_scene as A
from shafts_blender.convert import classes, export_scene, importer
from shafts_blender.convert.files import write_files

# The mean relative difference of the two renders over the lit pixels: the
# round trip moves the medium's box by 1e-4 of the scene (the writer's
# enlargement) and re-triangulates nothing else.
IMAGE_BOUND = 0.005
# The same with a light map, which the card's texture interpolation (and a
# window's wall, left to the format's rule) may move at texel edges.
MAP_BOUND = 0.01

SCENE = {
    "format": "shafts-scene", "version": 1,
    "camera": {"position": [0.5, 2.0, 7.0], "look_at": [0, 1, 0], "fov_y_deg": 40,
               "width": 48, "height": 36},
    "background": [0.01, 0.02, 0.03],
    "medium": {"sigma_s": [0.12, 0.1, 0.08], "sigma_a": [0.02, 0.02, 0.03],
               "phase": {"type": "henyey_greenstein", "g": 0.3},
               "bounds": {"min": [-4, 0, -4], "max": [4, 4, 4]}},
    "lights": [
        {"type": "spot", "position": [0, 3.5, 0], "direction": [0.1, -1, 0],
         "intensity": [40, 36, 30], "outer_angle_deg": 30, "inner_angle_deg": 20,
         "exponent": 1},
        {"type": "point", "position": [-2, 2.5, 1], "intensity": [3, 3, 4]},
        {"type": "directional", "direction": [0.3, -1, -0.2], "irradiance": [0.5, 0.5, 0.4]},
    ],
    "materials": {
        "floor": {"diffuse": [0.5, 0.5, 0.5]},
        "mirror": {"reflect": [0.8, 0.8, 0.8]},
        "glass": {"transmit": [0.9, 0.85, 0.8], "ior": 1.5},
        "lamp": {"emission": [2, 1.8, 1.5]},
    },
    "shapes": [
        {"type": "box", "material": "floor", "min": [-4, -0.2, -4], "max": [4, 0, 4]},
        {"type": "quad", "material": "mirror", "corner": [-2, 0, -2], "u": [1.5, 0, 0],
         "v": [0, 2, 0]},
        {"type": "box", "material": "glass", "min": [0.5, 0.5, -0.5], "max": [1.5, 1.5, 0.5],
         "transform": {"rotate_deg": [0, 30, 0]}},
        {"type": "quad", "material": "lamp", "corner": [1, 3, -2], "u": [0.5, 0, 0],
         "v": [0, 0, 0.5]},
    ],
}


def depsgraph():
    dg = bpy.context.evaluated_depsgraph_get()
    dg.update()
    return dg


def unit(v):
    v = np.asarray(v, dtype=float)
    return list(v / np.linalg.norm(v))


build = H.build_dir()
lib = os.path.join(build, "libshafts.so")
work = tempfile.mkdtemp(prefix="convert_roundtrip_")
src = os.path.join(work, "original.json")
with open(src, "w") as f:
    json.dump(SCENE, f)

# Import, as File > Import does.
A.reset()
notes = importer.import_scene(bpy.context, src, lib_path=lib)
H.check("the import made a camera, 3 lights, 4 shapes and the medium",
        len([o for o in bpy.data.objects if o.type == "LIGHT"]) == 3 and
        len([o for o in bpy.data.objects if o.type == "MESH"]) == 5, notes)

e = export_scene(depsgraph())
s = e.scene
H.check("no approximation back from Blender", not e.warnings, e.warnings)
H.check("the writer notes only Cycles' total internal reflection", len(notes) == 1
        and "total internal reflection" in notes[0], notes)

c0, c1 = SCENE["camera"], s["camera"]
H.near("camera position", c1["position"], c0["position"])
H.near("camera direction", unit(np.subtract(c1["look_at"], c1["position"])),
       unit(np.subtract(c0["look_at"], c0["position"])))
H.near("camera fov", c1["fov_y_deg"], c0["fov_y_deg"])
H.check("camera size", (c1["width"], c1["height"]) == (48, 36))
H.near("background", s["background"], SCENE["background"])

by_type = {l["type"]: l for l in s["lights"]}
H.check("three lights of the three types", len(s["lights"]) == 3 and len(by_type) == 3)
for l0 in SCENE["lights"]:
    l1 = by_type[l0["type"]]
    for key in ("position", "intensity", "irradiance", "outer_angle_deg",
                "inner_angle_deg", "exponent"):
        if key in l0:
            H.near("%s %s" % (l0["type"], key), l1[key], l0[key], 1e-5)
    if "direction" in l0:
        H.near("%s direction" % l0["type"], l1["direction"], unit(l0["direction"]))

m0, m1 = SCENE["medium"], s["medium"]
for key in ("sigma_s", "sigma_a"):
    H.near("medium %s" % key, m1[key], m0[key])
H.near("medium g", m1["phase"]["g"], 0.3)
H.near("medium bounds", m1["bounds"]["min"] + m1["bounds"]["max"],
       m0["bounds"]["min"] + m0["bounds"]["max"], 2e-3)

got = sorted(json.dumps(v, sort_keys=True) for v in
             ({k: [round(x, 5) for x in c] if isinstance(c, list) else round(c, 5)
               for k, c in m.items()} for m in s["materials"].values()))
want = sorted(json.dumps(v, sort_keys=True) for v in
              ({k: [round(float(x), 5) for x in c] if isinstance(c, list) else round(float(c), 5)
                for k, c in m.items()} for m in SCENE["materials"].values()))
H.check("the same materials", got == want, "got %s, want %s" % (got, want))

# The same image from the reference renderer.
out = os.path.join(work, "roundtrip.json")
write_files(e, out)
rel, _ = H.render_difference(build, src, out, work)
H.check("the round trip renders the same image (mean relative difference %.2g <= %g)"
        % (rel, IMAGE_BOUND), rel <= IMAGE_BOUND)

# A scene Cycles' single precision cannot hold in its own units: SCENE with
# every length times 1e-9 (coefficients over it, intensities times its
# square) is imported scaled back by the writer's frame (1e9, stated in a
# message and the collection's properties), and exports as SCENE, the same
# image (docs/scene_export.md, "Precision").
def scaled(o, k, key=""):
    if isinstance(o, dict):
        return {a: scaled(b, k, a) for a, b in o.items()}
    if isinstance(o, list):
        return [scaled(b, k, key) for b in o]
    if isinstance(o, (int, float)) and not isinstance(o, bool):
        if key in ("position", "look_at", "corner", "u", "v", "min", "max", "radius"):
            return o * k
        if key in ("sigma_s", "sigma_a"):
            return o / k
        if key == "intensity":
            return o * k * k
    return o


A.reset()
tiny = os.path.join(work, "tiny.json")
with open(tiny, "w") as f:
    json.dump(scaled(SCENE, 1e-9), f)
notes = importer.import_scene(bpy.context, tiny, lib_path=lib)
coll = bpy.context.scene.collection.children["tiny"]
H.check("a scene scaled by 1e-9 is imported scaled by 1e9, and says so",
        any("multiplied by 1e+09" in n for n in notes) and coll["shafts_scale"] == 1e9, notes)
e = export_scene(depsgraph())
out = os.path.join(work, "tiny_back.json")
write_files(e, out)
H.near("a scene scaled by 1e-9: the camera comes back in the scaled frame",
       e.scene["camera"]["position"], SCENE["camera"]["position"], 1e-4)
rel, _ = H.render_difference(build, src, out, work)
H.check("a scene scaled by 1e-9: the same image as the plain scene (mean relative "
        "difference %.2g <= %g)" % (rel, IMAGE_BOUND), rel <= IMAGE_BOUND)

# Light maps: the import's cards come back as the lights' maps.
testdata = os.path.join(os.path.dirname(os.path.dirname(H.HERE)), "scene_export", "testdata")
for name, kind in (("spot_gobo", "spot"), ("sun_window", "directional")):
    A.reset()
    path = H.scene_copy(os.path.join(testdata, name + ".json"), work, (64, 48))
    importer.import_scene(bpy.context, path, lib_path=lib)
    e = export_scene(depsgraph())
    light = next(l for l in e.scene["lights"] if l["type"] == kind)
    H.check("%s: the card comes back as the light's map, no warning" % name,
            "light_map" in light and not e.warnings, e.warnings)
    out = os.path.join(work, name + "_back.json")
    write_files(e, out)
    H.check("%s: the map is written beside the scene" % name,
            os.path.exists(os.path.join(work, name + "_back_map0.pfm")))
    rel, _ = H.render_difference(build, path, out, work)
    H.check("%s: the same image (mean relative difference %.2g <= %g)"
            % (name, rel, MAP_BOUND), rel <= MAP_BOUND)

# Phases Cycles cannot hold: the import says which engines are exact and how
# far Cycles' lobes are from the phase (importer.phase_messages; the
# largest relative error over every angle, computed from the writer's
# lobes), and the export gives our engines the scene's own phase back,
# exactly, with the coefficients and no warning. Changing a lobe's g in the
# node graph falls back to the graph's lobes.
PHASES = {"phase_rayleigh": ({"type": "rayleigh"}, "Rayleigh", "mixture of 2", "7.6%"),
          "phase_nishita_hazy": ({"type": "nishita_hazy"}, "Nishita hazy",
                                 "one Henyey-Greenstein lobe, g = 0.4,", "48%"),
          "phase_nishita_murky": ({"type": "nishita_murky"}, "Nishita murky",
                                  "one Henyey-Greenstein lobe, g = 0.567,", "252%")}
for name, (want_phase, label, lobes, figure) in PHASES.items():
    A.reset()
    path = H.scene_copy(os.path.join(testdata, name + ".json"), work, (32, 24))
    notes = importer.import_scene(bpy.context, path, lib_path=lib)
    said = [n for n in notes if "phase is exact in the Shafts Tracer and Shafts Sweep" in n]
    H.check("%s: one note says the %s phase is exact in our engines, and by how much "
            "Cycles is off" % (name, label),
            len(said) == 1 and ("the %s phase" % label) in said[0] and lobes in said[0]
            and ("up to %s off the phase" % figure) in said[0]
            and "EEVEE by one lobe" in said[0], notes)
    H.check("%s: the writer's bare 'Cycles has no ... phase' note is replaced" % name,
            not any("Cycles has no" in n for n in notes), notes)
    e = export_scene(depsgraph())
    with open(path) as f:
        m0 = json.load(f)["medium"]
    m1 = e.scene["medium"]
    H.check("%s: our engines get the scene's own phase, no warning" % name,
            m1["phase"] == want_phase and not e.warnings, str((m1["phase"], e.warnings)))
    for key in ("sigma_s", "sigma_a"):
        H.near("%s: medium %s" % (name, key), m1[key], m0[key])
    if name == "phase_rayleigh":
        mat = bpy.data.materials["medium"]
        lobe = next(nd for nd in mat.node_tree.nodes if nd.bl_idname == "ShaderNodeVolumeScatter")
        lobe.inputs["Anisotropy"].default_value = 0.5
        e = export_scene(depsgraph())
        H.check("phase_rayleigh: a lobe's g changed in Blender, the graph's lobes are read",
                e.scene["medium"]["phase"]["type"] == "henyey_greenstein"
                and any("scattering lobes" in w for w in e.warnings),
                str((e.scene["medium"]["phase"], e.warnings)))
A.reset()
cs = os.path.join(work, "cs.json")
with open(os.path.join(testdata, "point_medium.json")) as f:
    scene_cs = json.load(f)
scene_cs["medium"]["phase"] = {"type": "cornette_shanks", "g": 0.7}
with open(cs, "w") as f:
    json.dump(scene_cs, f)
notes = importer.import_scene(bpy.context, cs, lib_path=lib)
H.check("cornette_shanks: exact in our engines, Cycles' lobe 37% off at worst",
        any("the Cornette-Shanks (g = 0.7) phase is exact" in n and "up to 37% off" in n
            for n in notes), notes)
H.check("cornette_shanks: our engines get it back",
        export_scene(depsgraph()).scene["medium"]["phase"]
        == {"type": "cornette_shanks", "g": 0.7})

# A scene file the parser refuses: a located error, nothing imported.
bad = os.path.join(work, "bad.json")
with open(bad, "w") as f:
    f.write('{"format": "shafts-scene", "version": 1,\n "camera": {"position": [0, 0, 1]}}\n')
before = len(bpy.data.objects)
try:
    importer.import_scene(bpy.context, bad, lib_path=lib)
    H.check("a bad scene is refused", False)
except importer.ImportFailed as err:
    H.check("a bad scene is refused with its location", "bad.json:2:" in str(err), str(err))
H.check("nothing imported from a bad scene", len(bpy.data.objects) == before)

# File > Export's operator and tools/blend2shafts.
for cls in classes:
    bpy.utils.register_class(cls)
op_out = os.path.join(work, "op.json")
H.check("File > Export > Shafts scene",
        bpy.ops.shafts.export_scene(filepath=op_out) == {"FINISHED"}
        and os.path.exists(os.path.join(work, "op_mesh0.ply")))
blend = os.path.join(work, "scene.blend")
bpy.ops.wm.save_as_mainfile(filepath=blend)
tool = os.path.join(os.path.dirname(os.path.dirname(H.HERE)), "tools", "blend2shafts")
env = dict(os.environ, SHAFTS_BLENDER=bpy.app.binary_path)
r = subprocess.run([tool, blend, os.path.join(work, "cli.json")], capture_output=True,
                   text=True, env=env)
H.check("blend2shafts exports", r.returncode == 0 and
        os.path.exists(os.path.join(work, "cli.json")), r.stderr)


def without_files(path):
    with open(path) as f:
        scene = json.load(f)
    for shape in scene["shapes"]:
        shape.pop("file")
    for light in scene["lights"]:
        light.get("light_map", {}).pop("image", None)
    return scene


H.check("blend2shafts gives the operator's scene",
        without_files(os.path.join(work, "cli.json")) == without_files(op_out))
for args, what in (([], "no arguments"), ([blend], "one argument"),
                   ([os.path.join(work, "none.blend"), os.path.join(work, "x.json")],
                    "a missing .blend"),
                   ([src, os.path.join(work, "x.json")], "not a .blend"),
                   ([blend, os.path.join(work, "x.txt")], "not .json"),
                   ([os.path.join(work, "bad.blend"), os.path.join(work, "x.json")],
                    "a .blend Blender cannot open")):
    if what.startswith("a .blend Blender"):
        with open(os.path.join(work, "bad.blend"), "w") as f:
            f.write("not a blend file")
    r = subprocess.run([tool] + args, capture_output=True, text=True, env=env)
    H.check("blend2shafts: %s -> exit 2, nothing written" % what,
            r.returncode == 2 and not os.path.exists(os.path.join(work, "x.json")),
            "%d %s" % (r.returncode, r.stderr.strip()))
r = subprocess.run([tool, "--help"], capture_output=True, text=True)
H.check("blend2shafts --help", r.returncode == 0 and "usage:" in r.stdout)
r = subprocess.run([tool, "--version"], capture_output=True, text=True)
H.check("blend2shafts --version", r.returncode == 0 and
        r.stdout.startswith("blend2shafts ") and r.stdout.split()[1][:1].isdigit(), r.stdout)
H.check("File > Import > Shafts scene",
        bpy.ops.shafts.import_scene(filepath=op_out) == {"FINISHED"})
H.finish()
