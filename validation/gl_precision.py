"""Where single precision loses gl_shafts' far camera, quantity by quantity
(issue 11 kind 3, issue 12 part 5): prints the table of docs/gl_shafts.md
("Precision").

  python3 -m validation.gl_precision [--offset 1e7]

The scene is the precision tests' (validation/hard/cases.py base_scene: a
spot in a 4-unit box of fog over a floor, bounds' half diagonal R =
sqrt(12)), seen obliquely (30 degrees above and 20 degrees beside the spot's
axis, so that no component is exactly zero) from 1e2 to 1e7 scene radii,
optionally with the whole scene moved by --offset (1, -1, 1). For points of
the lit volume the script evaluates, in IEEE single precision (every
operation rounded to float32, as the shaders do it, without fused
multiply-adds), each quantity the sweep takes from the camera: once as GL saw
it before (everything counted from the eye: the eye in the anchored space,
view depths from the eye, the depth buffer's znear / z) and once as it does
now (counted from the scene's near end zref, the ray's point at depth zref
from double-precision uniforms, the depth buffer linear in zeta; gs_view.h),
against the same quantity in double precision. The worst error over the
points is printed, in the unit that decides what it does to the image:

- plane depth: a slab's depth as stored (float), in R;
- sample point: the ray's point at a sample's depth, in R;
- light's foot: t - b along the ray from the light's foot (the angle
  parametrisation of plane_local.frag), in R;
- shadow lookup: the 2D map's texture coordinates of a sample point, in
  texels of a 1024 map (the default);
- shadow depth: the point's reversed depth against the map's, as a
  fraction of the 1e-4 margin (VOLUME_MARGIN): above 1 a lit point reads as
  shadowed or the reverse;
- lattice: the lattice texture's layer coordinate (64 planes), in layers;
- eye path: the length from the box's entry to the sample (the
  transmittance towards the eye), in R;
- depth buffer: the least depth difference two surfaces need to be told
  apart, in R.

These are models of the shaders' arithmetic, not the GPU's own rounding
(llvmpipe may fuse a multiply and an add, which only helps); the images'
own errors come from validation/precision.py and extremes_test.
"""

import argparse
import math
import struct

R = math.sqrt(12.0)
BMIN, BMAX = (-2.0, 0.0, -2.0), (2.0, 4.0, 2.0)
LIGHT = (0.0, 3.8, 0.0)
SPOT_DIR = (0.0, -1.0, 0.0)
TAN_OUTER = math.tan(math.radians(30.0))
SHADOW_RES = 1024
LATTICE_LAYERS = 65
DISTANCES = [1e2, 1e3, 1e4, 1e5, 1e6, 1e7]


def f(x):
    """x rounded to the nearest float32."""
    return struct.unpack("f", struct.pack("f", x))[0]


def f_ulp(x):
    """The spacing of float32 at x."""
    b = struct.unpack("I", struct.pack("f", abs(f(x))))[0]
    return struct.unpack("f", struct.pack("I", b + 1))[0] - abs(f(x))


# Vectors as tuples; the f-prefixed operations round every result to float32.
def add(a, b): return tuple(x + y for x, y in zip(a, b))
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def scale(a, s): return tuple(x * s for x in a)
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def norm(a): return math.sqrt(dot(a, a))
def unit(a): return scale(a, 1.0 / norm(a))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0])
def fv(a): return tuple(f(x) for x in a)
def fadd(a, b): return tuple(f(x + y) for x, y in zip(a, b))
def fsub(a, b): return tuple(f(x - y) for x, y in zip(a, b))
def fscale(a, s): return tuple(f(x * s) for x in a)


def fdot(a, b):
    s = f(a[0] * b[0])
    for x, y in zip(a[1:], b[1:]):
        s = f(s + f(x * y))
    return s


def anchor_of(lo, hi):
    """sh_frame_fit's origin."""
    c = scale(add(lo, hi), 0.5)
    r = 0.5 * norm(sub(hi, lo))
    u = 2.0 ** math.ceil(math.log2(r))
    return tuple(u * math.floor(x / u + 0.5) if x >= 0 else -u * math.floor(-x / u + 0.5)
                 for x in c)


def camera(distance, offset):
    look = add((0.0, 1.5, 0.0), offset)
    el, az = math.radians(30.0), math.radians(20.0)
    back = (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))
    eye = add(look, scale(back, distance))
    fwd = scale(back, -1.0)
    right = unit(cross(fwd, (0.0, 1.0, 0.0)))
    up = cross(right, fwd)
    return eye, fwd, right, up


def sample_points(offset):
    """Points of the spot's lit cone inside the box."""
    pts = []
    for i in range(5):
        for j in range(5):
            for k in range(4):
                y = 0.2 + 0.8 * k
                r = (3.8 - y) * TAN_OUTER * 0.9
                x, z = r * (i / 2.0 - 1.0), r * (j / 2.0 - 1.0)
                if abs(x) < 2 and abs(z) < 2:
                    pts.append(add((x, y, z), offset))
    return pts


def box_entry(o, d, lo, hi):
    """The ray parameter where o + t d enters the box [lo, hi] (double)."""
    t0 = -math.inf
    for k in range(3):
        if d[k] != 0:
            a, b = (lo[k] - o[k]) / d[k], (hi[k] - o[k]) / d[k]
            t0 = max(t0, min(a, b))
    return t0


def fbox_entry(o, d, lo, bmin, bmax):
    """box_clip's entry in float32 (common.glsl), with the lower bound lo."""
    t0 = lo
    for k in range(3):
        inv = f(1.0 / d[k])
        a, b = f(f(bmin[k] - o[k]) * inv), f(f(bmax[k] - o[k]) * inv)
        t0 = max(t0, min(a, b))
    return t0


def spot_lookup(p, lpos, near):
    """The spot's 2D shadow-map coordinates (s, t) and reversed depth of p
    (gs_lightvol.c shadow_2d_spot, common.glsl shadow_coord), in double."""
    r, u = unit(cross(SPOT_DIR, (0.0, 0.0, 1.0))), None
    u = cross(r, SPOT_DIR)
    v = sub(p, lpos)
    w = dot(SPOT_DIR, v)
    k = 1.0 / TAN_OUTER
    return (0.5 + 0.5 * k * dot(r, v) / w, 0.5 + 0.5 * k * dot(u, v) / w, near / w)


def fspot_lookup(p, lpos_a, near):
    """The same lookup in float32 from an anchored float point, with the
    matrix's translation folded in double as gs_params.c does."""
    r = unit(cross(SPOT_DIR, (0.0, 0.0, 1.0)))
    u = cross(r, SPOT_DIR)
    k = 1.0 / TAN_OUTER
    rows = [scale(r, 0.5 * k), scale(u, 0.5 * k), SPOT_DIR]
    m = [(fv(rw), f(-dot(rw, lpos_a))) for rw in rows]
    x, y, w = (f(fdot(a, p) + b) for a, b in m)
    w2 = f(w + 0.0)
    return f(f(x / w2) + 0.5), f(f(y / w2) + 0.5), f(near / w2)


def measure(distance_radii, offset_len):
    off = scale((1.0, -1.0, 1.0), offset_len)
    lo, hi = add(BMIN, off), add(BMAX, off)
    anchor = anchor_of(lo, hi)
    dist = distance_radii * R
    eye, fwd, right, up = camera(dist, off)
    lpos = add(LIGHT, off)
    lpos_a = fv(sub(lpos, anchor))
    bmin_a, bmax_a = fv(sub(lo, anchor)), fv(sub(hi, anchor))
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    za = dot(sub(anchor, eye), fwd)
    c = [dot(sub(q, anchor), fwd) for q in corners]
    size = norm(sub(hi, lo))
    znear = 1e-5 * size
    zref, depth_a, depth_b = 0.0, 0.0, znear
    if za + min(c) > znear:
        zref = za + min(c)
        depth_a, depth_b = zref / (2.0 * (max(c) - min(c))), zref
    org = add(sub(eye, anchor), scale(fwd, zref))
    zmin = min(dot(sub(q, eye), fwd) for q in corners)
    zmax = max(dot(sub(q, eye), fwd) for q in corners)
    shadow_near = 1e-4 * size
    worst = {}

    def note(key, old, new):
        o, n = worst.get(key, (0.0, 0.0))
        worst[key] = (max(o, old), max(n, new))

    for P in sample_points(off):
        z = dot(sub(P, eye), fwd)
        d = scale(sub(P, eye), 1.0 / z)   # d . fwd = 1, exact in double
        dd = fv(d)
        dl = norm(d)
        dn = unit(d)
        fdn = fv(dn)
        p_true = sub(P, anchor)
        # Plane depth.
        note("plane depth", abs(f(z) - z) / R, abs(f(z - zref) - (z - zref)) / R)
        # The sample point: old eye + z d, new o + zeta d.
        eye_a = fv(sub(eye, anchor))
        p_old = fadd(eye_a, fscale(dd, f(z)))
        o_new = fadd(fv(org), fscale(fv(sub(d, fwd)), f(zref)))
        zeta = f(z - zref)
        p_new = fadd(o_new, fscale(dd, zeta))
        note("sample point", norm(sub(p_old, p_true)) / R, norm(sub(p_new, p_true)) / R)
        # The light's foot: t - b, t the ray length to the sample, b to the foot.
        tb_true = dot(sub(P, lpos), dn)
        b_old = -fdot(fsub(eye_a, lpos_a), fdn)
        tb_old = f(f(f(z) * f(dl)) - b_old)
        b_new = -fdot(fsub(o_new, lpos_a), fdn)
        tb_new = f(f(zeta * f(dl)) - b_new)
        note("light's foot", abs(tb_old - tb_true) / R, abs(tb_new - tb_true) / R)
        # The shadow lookup and depth compare.
        s0, t0, q0 = spot_lookup(P, lpos, shadow_near)
        s1, t1, q1 = fspot_lookup(p_old, lpos_a, shadow_near)
        s2, t2, q2 = fspot_lookup(p_new, lpos_a, shadow_near)
        note("shadow lookup", max(abs(s1 - s0), abs(t1 - t0)) * SHADOW_RES,
             max(abs(s2 - s0), abs(t2 - t0)) * SHADOW_RES)
        note("shadow depth", abs(q1 / q0 - 1) / 1e-4, abs(q2 / q0 - 1) / 1e-4)
        # The lattice's layer: r = z map4 + map5 (gs_lattice.c).
        m4 = 1.0 / ((zmax - zmin) / (LATTICE_LAYERS - 1) * LATTICE_LAYERS)
        r_true = 0.5 / LATTICE_LAYERS + (z - zmin) * m4
        r_old = f(f(f(z) * f(m4)) + f(0.5 / LATTICE_LAYERS - zmin * m4))
        r_new = f(f(zeta * f(m4)) + f(0.5 / LATTICE_LAYERS - (zmin - zref) * m4))
        note("lattice", abs(r_old - r_true) * LATTICE_LAYERS, abs(r_new - r_true) * LATTICE_LAYERS)
        # The eye path: from the box's entry to the sample.
        te = box_entry(eye, d, lo, hi)
        len_true = (z - te) * dl
        e_old = fbox_entry(eye_a, dd, 0.0, bmin_a, bmax_a)
        e_new = fbox_entry(o_new, dd, f(-zref), bmin_a, bmax_a)
        note("eye path", abs(f(f(f(z) - e_old) * f(dl)) - len_true) / R,
             abs(f(f(zeta - e_new) * f(dl)) - len_true) / R)
        # The depth buffer: the depth difference of one ulp of the value.
        old_val = znear / z
        res_old = f_ulp(old_val) / (znear / (z * z))
        new_val = (depth_b - depth_a * (z - zref)) / z
        slope = abs((-depth_a * z - (depth_b - depth_a * (z - zref))) / (z * z))
        note("depth buffer", res_old / R, f_ulp(new_val) / slope / R)
    return worst


def cell(x):
    if x == 0:
        return "0"
    return "%.1g" % x


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--offset", type=float, default=0.0,
                    help="move the scene by this times (1, -1, 1)")
    args = ap.parse_args(argv)
    rows = [measure(d, args.offset) for d in DISTANCES]
    keys = list(rows[0].keys())
    unit_of = {"shadow lookup": "texels", "shadow depth": "margins", "lattice": "layers"}
    print("Worst error, before (from the eye) / now (from zref), the scene moved by %g:\n"
          % args.offset)
    print("| quantity (unit) | " + " | ".join("%g R" % d for d in DISTANCES) + " |")
    print("|---" * (len(DISTANCES) + 1) + "|")
    for k in keys:
        print("| %s (%s) | %s |" % (k, unit_of.get(k, "R"), " | ".join(
            "%s / %s" % (cell(r[k][0]), cell(r[k][1])) for r in rows)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
