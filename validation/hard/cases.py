"""The hard cases: scenes that push a renderer where single scattering is
hard, one `Case` each in CASES (validation/hard/bounds.py states what each
renderer must reach on them; validation/hard/runner.py renders and checks).

Adding a case is adding a builder `(width, height) -> scene dict` and an
entry to CASES, plus a bound in bounds.py where a renderer's default bound
does not hold for it.
"""

import copy
import json
import math
from pathlib import Path
from dataclasses import dataclass, field

# Scene construction.

BOX = {"min": [-2.0, 0.0, -2.0], "max": [2.0, 4.0, 2.0]}  # the medium: size 4

# Inputs from reports (issue 11) and their variants.
TESTDATA = Path(__file__).resolve().parents[2] / "testdata" / "hard_cases"


def base_scene(width, height):
    """A spot light shining down through a medium box onto a dim floor, with
    a black sphere casting a volumetric shadow: the control the cases vary.
    The sphere is black and the light just above the frame so that the
    image is shafts and floor: a lit sphere's few bright pixels, or the
    unbounded radiance next to a light in view, would dominate the relative
    RMS error (the cases that put a light in view say so)."""
    return {
        "format": "shafts-scene", "version": 1,
        "camera": {"position": [0.0, 1.5, 7.0], "look_at": [0.0, 1.5, 0.0],
                   "fov_y_deg": 30.0, "width": width, "height": height},
        "medium": {"sigma_s": [0.3, 0.3, 0.3], "sigma_a": [0.03, 0.03, 0.03],
                   "phase": {"type": "henyey_greenstein", "g": 0.3},
                   "bounds": copy.deepcopy(BOX)},
        "lights": [{"type": "spot", "position": [0.0, 3.8, 0.0], "direction": [0.0, -1.0, 0.0],
                    "intensity": [10.0, 10.0, 10.0], "outer_angle_deg": 30.0,
                    "inner_angle_deg": 20.0, "exponent": 1.0}],
        "materials": {"floor": {"diffuse": [0.3, 0.3, 0.3]},
                      "black": {"diffuse": [0.0, 0.0, 0.0]}},
        "shapes": [{"type": "quad", "material": "floor", "corner": [-2.0, 0.0, 2.0],
                    "u": [4.0, 0.0, 0.0], "v": [0.0, 0.0, -4.0]},
                   {"type": "sphere", "material": "black", "center": [0.35, 2.4, 0.1],
                    "radius": 0.35}],
        "render": {"spp": 16, "seed": 0},
    }


def scaled(scene, s):
    """The scene with every length multiplied by s, the coefficients per
    unit length divided by s and the intensities of point and spot lights
    multiplied by s^2, which leaves the image unchanged (radiance is
    invariant: optical depths, solid angles and irradiances all are)."""
    out = copy.deepcopy(scene)
    cam = out["camera"]
    for k in ("position", "look_at"):
        cam[k] = [c * s for c in cam[k]]
    m = out.get("medium")
    if m:
        m["sigma_s"] = [c / s for c in m["sigma_s"]]
        m["sigma_a"] = [c / s for c in m.get("sigma_a", [0, 0, 0])]
        m["bounds"] = {k: [c * s for c in v] for k, v in m["bounds"].items()}
    for light in out.get("lights", []):
        for k in ("position", "look_at"):
            if k in light:
                light[k] = [c * s for c in light[k]]
        if light["type"] in ("point", "spot"):
            light["intensity"] = [c * s * s for c in light["intensity"]]
        lm = light.get("light_map")
        if lm and "origin" in lm:
            for k in ("origin", "u", "v"):
                lm[k] = [c * s for c in lm[k]]
    for shape in out.get("shapes", []):
        for k in ("corner", "u", "v", "center", "min", "max", "base", "top"):
            if k in shape:
                shape[k] = [c * s for c in shape[k]]
        if "radius" in shape:
            shape["radius"] *= s
        if "transform" in shape:
            raise ValueError("scaled() handles untransformed shapes only")
    return out


def _norm(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


@dataclass
class Case:
    """One hard case: how to build its scene, what to check."""

    name: str
    description: str
    build: object                      # (width, height) -> scene dict
    odd: bool = False                  # odd image size (a pixel centre on the axis)
    mask_lights: bool = False          # mask the pixels next to visible lights
    only: tuple = ()                   # renderers it applies to (empty: all)
    extra: dict = field(default_factory=dict)   # renderer -> [(label, params)]
    invariance: tuple = ()             # (kind, other case name) checks
    black: bool = False                # the truth is 0 everywhere: so must every image be
    # The case whose reference is the truth for this one (a scaled scene's
    # true image is its base scene's); None: its own reference.
    reference_case: str = None


def moved(scene, offset):
    """The scene with every position moved by offset, which leaves the
    image unchanged."""
    out = copy.deepcopy(scene)

    def add(p):
        return [c + o for c, o in zip(p, offset)]
    cam = out["camera"]
    for k in ("position", "look_at"):
        cam[k] = add(cam[k])
    m = out.get("medium")
    if m:
        m["bounds"] = {k: add(v) for k, v in m["bounds"].items()}
    for light in out.get("lights", []):
        for k in ("position", "look_at"):
            if k in light:
                light[k] = add(light[k])
        lm = light.get("light_map")
        if lm and "origin" in lm:
            lm["origin"] = add(lm["origin"])
    for shape in out.get("shapes", []):
        for k in ("corner", "center", "min", "max", "base", "top"):
            if k in shape:
                shape[k] = add(shape[k])
        if "transform" in shape:
            raise ValueError("moved() handles untransformed shapes only")
    return out


def camera_at(distance):
    """A builder of the base scene seen from `distance` units away along
    the same axis, with the field of view that keeps the framing at the
    spot's axis (the perspective flattens as the camera recedes)."""
    def build(w, h):
        s = base_scene(w, h)
        cam = s["camera"]
        near = cam["position"][2] - cam["look_at"][2]
        half = near * math.tan(math.radians(cam["fov_y_deg"] / 2))
        cam["position"][2] = cam["look_at"][2] + distance
        cam["fov_y_deg"] = math.degrees(2 * math.atan(half / distance))
        return s
    return build


def _point_in_view(w, h):
    s = base_scene(w, h)
    s["lights"] = [{"type": "point", "position": [0.0, 1.8, 0.0], "intensity": [6.0, 6.0, 6.0]}]
    s["camera"]["look_at"] = [0.0, 1.8, 0.0]
    s["camera"]["position"] = [0.0, 1.8, 7.0]
    return s


def _light_on_plane(w, h):
    # The box's depth range seen from the camera is [5, 9]; the light sits
    # at its middle, depth 7: a slab boundary of a regular sweep over the
    # box with an even number of planes, a slab's sample depth with an odd
    # number (gl_shafts renders both: planes 100 and 101).
    s = base_scene(w, h)
    s["camera"]["position"] = [0.0, 2.0, 7.0]
    s["camera"]["look_at"] = [0.0, 2.0, 0.0]
    s["camera"]["fov_y_deg"] = 50.0
    s["lights"] = [{"type": "point", "position": [0.7, 2.3, 0.0], "intensity": [6.0, 6.0, 6.0]}]
    s["shapes"] = [sh for sh in s["shapes"] if sh["type"] == "sphere"]
    s["shapes"][0]["center"] = [0.0, 1.6, 0.5]
    return s


def _inside_spot_cone(w, h):
    s = base_scene(w, h)
    s["camera"]["position"] = [0.25, 0.6, 0.3]
    s["camera"]["look_at"] = [0.0, 3.8, 0.0]
    s["camera"]["up"] = [0.0, 0.0, -1.0]
    s["camera"]["fov_y_deg"] = 60.0
    s["shapes"][1]["center"] = [0.6, 2.4, 0.0]
    s["shapes"][1]["radius"] = 0.3
    return s


def _dense(w, h):
    # sigma_t * size = 12.5 * 4 = 50: light enters the box's front face and
    # dies within 1/sigma_t = 0.08 units.
    s = base_scene(w, h)
    s["medium"]["sigma_s"] = [10.0, 10.0, 10.0]
    s["medium"]["sigma_a"] = [2.5, 2.5, 2.5]
    s["lights"] = [{"type": "spot", "position": [0.0, 4.5, 4.5], "look_at": [0.0, 2.0, 2.0],
                    "intensity": [40.0, 40.0, 40.0], "outer_angle_deg": 30.0,
                    "inner_angle_deg": 20.0, "exponent": 1.0}]
    s["shapes"][1]["center"] = [0.3, 3.0, 3.0]
    s["shapes"][1]["radius"] = 0.3
    return s


def _thin(w, h):
    # sigma_t * size = 1e-6: the image is in-scattering alone, of the order
    # of 1e-8 of the light's intensity (no surfaces, black background).
    s = base_scene(w, h)
    s["medium"]["sigma_s"] = [2e-7, 2e-7, 2e-7]
    s["medium"]["sigma_a"] = [5e-8, 5e-8, 5e-8]
    s["shapes"] = []
    return s


def _murky(w, h):
    # A spot behind the medium shines at the camera: the phase angle is
    # small near its axis, where the murky peak (1 + 50 cos^64(alpha/2))
    # is, and the sphere's shadow runs towards the camera.
    s = base_scene(w, h)
    s["medium"]["phase"] = {"type": "nishita_murky"}
    s["lights"] = [{"type": "spot", "position": [0.4, 2.4, -1.8], "look_at": [0.0, 1.9, 7.0],
                    "intensity": [5.0, 5.0, 5.0], "outer_angle_deg": 25.0,
                    "inner_angle_deg": 15.0, "exponent": 1.0}]
    s["shapes"][1]["center"] = [0.2, 2.1, -0.6]
    s["shapes"][1]["radius"] = 0.3
    return s


def _grazing(w, h):
    # The camera looks down -z; the planes are z = constant; the light
    # travels almost along x, 1.1 degrees off the planes (and 6.8 degrees
    # down).
    s = base_scene(w, h)
    s["camera"]["look_at"] = [0.0, 2.0, 0.0]
    s["camera"]["position"] = [0.0, 2.0, 7.0]
    s["lights"] = [{"type": "directional", "direction": _norm([1.0, -0.12, 0.02]),
                    "irradiance": [2.0, 2.0, 2.0]}]
    s["shapes"][1]["center"] = [-1.2, 2.3, 0.0]
    return s


def _hard_spot(w, h):
    s = base_scene(w, h)
    light = s["lights"][0]
    light["inner_angle_deg"] = light["outer_angle_deg"] = 25.0
    light["exponent"] = 0.0
    return s


def _behind_camera(w, h):
    s = base_scene(w, h)
    s["medium"]["bounds"] = {"min": [-2.0, 0.0, -2.0], "max": [2.0, 4.0, 10.0]}
    s["shapes"][0]["v"] = [0.0, 0.0, -12.0]
    s["shapes"][0]["corner"] = [-2.0, 0.0, 10.0]
    s["lights"] = [{"type": "spot", "position": [0.3, 2.6, 9.0], "look_at": [0.0, 1.2, 0.0],
                    "intensity": [60.0, 60.0, 60.0], "outer_angle_deg": 16.0,
                    "inner_angle_deg": 10.0, "exponent": 1.0}]
    s["shapes"][1]["center"] = [0.2, 2.0, 3.5]
    s["shapes"][1]["radius"] = 0.3
    return s


def _handed(name):
    """A builder for one of testdata/hard_cases/ (issue 11's inputs and
    their variants, made by make_variants.py there) at the suite's size."""
    def build(w, h):
        with open(TESTDATA / (name + ".json")) as f:
            scene = json.load(f)
        scene["camera"]["width"], scene["camera"]["height"] = w, h
        return scene
    return build


def _far_moved(w, h):
    # 5e7 times the bounds' half diagonal, sqrt(12).
    return moved(camera_at(5e7 * math.sqrt(12.0))(w, h), (1e7, -1e7, 1e7))


def _pixel(w, h, n=1):
    # In the base scene the centre ray lies in the plane x = 0 through the
    # light that touches the sphere: it grazes the edge of the sphere's
    # shadow along a long stretch, where a shadow map's texel decides (gl_shafts
    # was 4% dark there). That is a test of shadow maps at tangency, not of a
    # 1x1 image, so the sphere moves off it here.
    s = base_scene(n, n)
    s["shapes"][1]["center"][0] = 0.5
    return s


def _pixel3(w, h):
    return _pixel(w, h, 3)


def _scale_case(exponent):
    """scale_1e<exponent>: the base scene scaled by 10^exponent, whose true
    image is the base scene's."""
    s = 10.0 ** exponent
    return Case("scale_1e%d" % exponent,
                "the base scene with all lengths times 1e%d, sigma times 1e%d, intensity "
                "times 1e%d: the same image" % (exponent, -exponent, 2 * exponent),
                lambda w, h: scaled(base_scene(w, h), s),
                invariance=(("scale", "base"),), reference_case="base")


CASES = [
    Case("base", "the control: a spot through a medium box, a sphere's shadow", base_scene),
    Case("point_light_in_view", "the camera looks straight at a point light inside "
         "the medium: the centre pixel's ray passes through the light (1/r^2 on the ray)",
         _point_in_view, odd=True, mask_lights=True),
    Case("light_on_plane", "a point light at the middle of the medium's depth range: "
         "on a plane boundary of the sweep with 100 planes, on a slab's sample depth with 101",
         _light_on_plane, mask_lights=True,
         extra={"gl_shafts": [("planes 100", {"planes": 100}), ("planes 101", {"planes": 101})]},
         invariance=(("plane", None),)),
    Case("inside_spot_cone", "the camera inside a spot's cone, looking up it at the light",
         _inside_spot_cone, mask_lights=True),
    Case("dense", "a very dense medium: sigma_t times the medium's size = 50", _dense),
    Case("thin", "a very thin medium: sigma_t times the medium's size = 1e-6, "
         "in-scattering alone", _thin),
    Case("planes_2000", "the base scene swept with 2000 planes", base_scene,
         only=("gl_shafts",), extra={"gl_shafts": [("planes 2000", {"planes": 2000})]}),
    *[_scale_case(e) for e in (-3, 4, -9, 9)],
    Case("moved_1e6", "the base scene moved by (1e6, -1e6, 1e6), far from the origin: "
         "the same image", lambda w, h: moved(base_scene(w, h), (1e6, -1e6, 1e6)),
         invariance=(("position", "base"),), reference_case="base"),
    Case("camera_500", "the base scene seen from 500 units away, the field of view "
         "(0.43 degrees) keeping the framing", camera_at(500.0)),
    Case("camera_5000", "the base scene seen from 5000 units away at 0.043 degrees: "
         "camera_500's image but for the perspective (0.35% in the reference)",
         camera_at(5000.0), invariance=(("distance", "camera_500"),)),
    Case("camera_5e7_radii", "the base scene seen from 5e7 scene radii (1.7e8 units, "
         "1.6e-6 degrees) and moved 1e7 from the origin (issue 12, part 5): camera_500's "
         "image but for the perspective", _far_moved),
    Case("murky_peak", "the murky phase function's forward peak: a spot shines at the camera",
         _murky, mask_lights=True),
    Case("grazing_directional", "a directional light travelling 1.1 degrees off the "
         "virtual planes (almost perpendicular to the view)", _grazing),
    Case("hard_spot", "a hard-edged spot: inner angle = outer angle, exponent 0", _hard_spot),
    Case("light_behind_camera", "a spot behind the camera shining past it into the view",
         _behind_camera),
    Case("image_3x3", "the base scene at 3x3 pixels (for the 1x1 invariance)", _pixel3),
    Case("image_1x1", "a 1x1 image: its pixel is the centre pixel of the 3x3 image",
         _pixel, invariance=(("pixel", "image_3x3"),)),
    Case("narrow_spot", "a 0.3-degree spot (a laser) in fog, the light in view: the "
         "beam is thinner than a pixel (issue 11, kind 1)", _handed("narrow_spot")),
    Case("closed_room", "a closed room of zero-thickness walls, the sun outside, the "
         "camera inside: black (issue 11, kind 2)", _handed("closed_room"), black=True),
    Case("surface_room", "the closed room with no medium (surfaces only): black; "
         "a floor at the foot of a wall the sun grazes took light", _handed("surface_room"),
         black=True),
    Case("window_room", "the closed room with a 1 x 1 window in its sunlit wall: a "
         "shaft through it", _handed("window_room")),
    Case("spot_blocked", "a plate 0.005 below a spot blocks its whole cone: black",
         _handed("spot_blocked_near"), black=True),
    Case("light_in_box", "a point light inside a closed box of six quads: black "
         "outside, no halo", _handed("light_in_quads"), black=True),
]


