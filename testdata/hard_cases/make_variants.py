#!/usr/bin/env python3
"""Writes the variants of the hard cases closed_room.json and narrow_spot.json
(issue 11, kinds 1 and 2) next to this script: the closed room lit from
other directions, moved far from the origin, with a window; a spot whose
whole cone a plate close to it blocks; a point light inside a closed box
(one box shape, and six quads). Run it after changing a case; the tests
(gl_shafts/thin_geometry_test.c, lmm_tracer/lmm_volume_test.c, the hard
cases of validation/hard/cases.py) read the files.

    python3 testdata/hard_cases/make_variants.py
"""
import copy
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def load(name):
    with open(os.path.join(HERE, name)) as f:
        return json.load(f)


def save(name, scene):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


def moved(scene, off):
    """The scene with every position moved by off."""
    s = copy.deepcopy(scene)
    add = lambda p: [a + b for a, b in zip(p, off)]
    s["camera"]["position"] = add(s["camera"]["position"])
    s["camera"]["look_at"] = add(s["camera"]["look_at"])
    if "medium" in s:
        b = s["medium"]["bounds"]
        b["min"], b["max"] = add(b["min"]), add(b["max"])
    for shape in s["shapes"]:
        shape["corner"] = add(shape["corner"])
    return s


def quad(c, u, v, material="wall"):
    return {"type": "quad", "material": material, "corner": c, "u": u, "v": v}


def box_scene(shapes):
    return {
        "format": "shafts-scene", "version": 1,
        "camera": {"position": [0, 1.5, 6], "look_at": [0, 1.2, 0], "fov_y_deg": 45,
                   "width": 64, "height": 48},
        "medium": {"sigma_s": [0.3, 0.3, 0.3], "sigma_a": [0.02, 0.02, 0.02],
                   "bounds": {"min": [-3, 0, -3], "max": [3, 4, 3]}},
        "lights": [],
        "materials": {"wall": {"diffuse": [0.5, 0.5, 0.5]}},
        "shapes": [quad([-3, 0, 3], [6, 0, 0], [0, 0, -6])] + shapes,
    }


def main():
    room = load("closed_room.json")
    room["camera"]["width"], room["camera"]["height"] = 64, 48
    for name, direction in [("closed_room_sun_behind", [0.6, -0.7, -0.4]),
                            ("closed_room_sun_high", [0.1, -1, 0.05]),
                            ("closed_room_sun_grazing", [-1, -0.08, 0.03])]:
        s = copy.deepcopy(room)
        s["lights"][0]["direction"] = direction
        save(name + ".json", s)
    save("closed_room_far.json", moved(room, [100, 50, -100]))
    # A 1 x 1 window in the lit wall (x = 2): the wall as four quads.
    s = copy.deepcopy(room)
    s["shapes"] = s["shapes"][:5] + [
        quad([2, 0, -2], [0, 0, 1.5], [0, 3, 0]), quad([2, 0, 0.5], [0, 0, 1.5], [0, 3, 0]),
        quad([2, 0, -0.5], [0, 0, 1], [0, 1.2, 0]), quad([2, 2.2, -0.5], [0, 0, 1], [0, 0.8, 0])]
    save("window_room.json", s)
    # A spot whose whole cone a plate just below it blocks.
    for name, gap in [("spot_blocked", 0.05), ("spot_blocked_near", 0.005)]:
        s = box_scene([quad([-0.5, 3 - gap, 0.5], [1, 0, 0], [0, 0, -1])])
        s["lights"] = [{"type": "spot", "position": [0, 3, 0], "look_at": [0.2, 0, 0.1],
                        "intensity": [50, 50, 50], "outer_angle_deg": 30}]
        save(name + ".json", s)
    # A point light inside a closed box: a box shape, and six quads.
    light = [{"type": "point", "position": [0.1, 1.5, 0.05], "intensity": [20, 20, 20]}]
    s = box_scene([{"type": "box", "material": "wall", "min": [-0.5, 1, -0.5],
                    "max": [0.5, 2, 0.5]}])
    s["lights"] = light
    save("light_in_box.json", s)
    lo, hi, faces = [-0.5, 1, -0.5], [0.5, 2, 0.5], []
    for axis in range(3):
        for side in (lo, hi):
            c, u, v = list(lo), [0, 0, 0], [0, 0, 0]
            c[axis] = side[axis]
            a1, a2 = [i for i in range(3) if i != axis]
            u[a1], v[a2] = hi[a1] - lo[a1], hi[a2] - lo[a2]
            faces.append(quad(c, u, v))
    s = box_scene(faces)
    s["lights"] = light
    save("light_in_quads.json", s)
    surface_rooms(room)


def scaled_room(room, size):
    """The closed room (surfaces only) with its walls spanning size (x, y,
    z) from its floor's centre, the camera kept inside at the same
    fractions."""
    s = copy.deepcopy(room)
    del s["medium"]
    k = [size[0] / 4.0, size[1] / 3.0, size[2] / 4.0]
    scale = lambda p: [p[0] * k[0], p[1] * k[1], p[2] * k[2]]
    s["camera"]["position"] = scale(s["camera"]["position"])
    s["camera"]["look_at"] = scale(s["camera"]["look_at"])
    for shape in s["shapes"]:
        for key in ("corner", "u", "v"):
            shape[key] = scale(shape[key])
    return s


def surface_rooms(room):
    """The closed room without a medium (surfaces only; issue 11's leftover:
    two floor pixels at a grazing wall's foot took light), in other sizes,
    lit by the sun from other directions, by a spot and a point light
    outside, and far from the origin."""
    base = scaled_room(room, [4, 3, 4])
    save("surface_room.json", base)
    for name, direction in [("sun_behind", [0.6, -0.7, -0.4]),
                            ("sun_grazing", [-1, -0.08, 0.03]),
                            ("sun_corner", [-0.7, -0.2, 0.7]),
                            ("sun_below", [-1, 0.45, 0.15])]:
        s = copy.deepcopy(base)
        s["lights"][0]["direction"] = direction
        save("surface_room_%s.json" % name, s)
    for name, size in [("small", [0.5, 0.4, 0.5]), ("long", [12, 3, 2]),
                       ("tall", [2, 9, 3])]:
        save("surface_room_%s.json" % name, scaled_room(room, size))
    s = copy.deepcopy(base)
    s["lights"] = [{"type": "spot", "position": [6, 4.5, -1], "look_at": [0, 0, 0],
                    "intensity": [80, 80, 80], "outer_angle_deg": 40}]
    save("surface_room_spot.json", s)
    s = copy.deepcopy(base)
    s["lights"] = [{"type": "point", "position": [3, 3.6, -2.6],
                    "intensity": [40, 40, 40]}]
    save("surface_room_point.json", s)
    save("surface_room_far.json", moved(base, [1000, 500, -1000]))


if __name__ == "__main__":
    main()
