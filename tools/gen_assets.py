#!/usr/bin/env python3
"""Generates the assets of the canonical scenes into scenes/assets/.

Everything is procedural and deterministic (fixed seeds), written with the
Python standard library only: PNGs through zlib and struct, the mesh as OBJ
text. Run it from anywhere:

    python3 tools/gen_assets.py [output_dir]

Outputs (output_dir defaults to scenes/assets next to this script's parent):
  teapot.obj          a closed-ish teapot: lathe-revolved body with lid and
                      knob, a swept tapering spout and a swept handle arc,
                      counter-clockwise outward triangles
  gobo_dots.png       polka dots, white on black, 128x128 grey (seed 000 fig 7b)
  gobo_star.png       a six-pointed star with a ring, 128x128 grey (fig 7b)
  terrain.png         mountain ridges, 128x128 grey heightfield (fig 8a)
  valley.png          a valley between two ridges, the right one notched,
                      128x128 grey heightfield (issue 12's valley in fog)
  stained_glass.png   coloured panes and lead lines, 128x128 RGB (fig 8b)
"""

import math
import os
import random
import struct
import sys
import zlib


# ---------------------------------------------------------------- PNG output

def srgb_encode(v):
    """Linear [0, 1] to an 8-bit sRGB code, rounded to nearest."""
    v = min(max(v, 0.0), 1.0)
    if v <= 0.0031308:
        s = 12.92 * v
    else:
        s = 1.055 * v ** (1 / 2.4) - 0.055
    return int(round(s * 255))


def write_png(path, width, height, channels, rows, linear_data=False):
    """Writes 8-bit grey (channels 1) or RGB (3) rows of code values, tagged
    sRGB, or linear (a gAMA chunk of 1.0) when linear_data is set."""
    def chunk(kind, data):
        body = kind + data
        return (struct.pack(">I", len(data)) + body
                + struct.pack(">I", zlib.crc32(body) & 0xffffffff))
    colour_type = {1: 0, 3: 2}[channels]
    raw = bytearray()
    for row in rows:
        assert len(row) == width * channels
        raw.append(0)  # filter: none
        raw.extend(row)
    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8,
                                      colour_type, 0, 0, 0))
    if linear_data:
        png += chunk(b"gAMA", struct.pack(">I", 100000))
    else:
        png += chunk(b"sRGB", b"\x00")
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def supersample(width, height, fn, n=4):
    """Averages fn(u, v) (u, v in [0, 1], v downwards) over n x n samples per
    pixel, returning rows of linear values (floats or tuples)."""
    out = []
    for y in range(height):
        row = []
        for x in range(width):
            acc = None
            for j in range(n):
                for i in range(n):
                    val = fn((x + (i + 0.5) / n) / width,
                             (y + (j + 0.5) / n) / height)
                    if acc is None:
                        acc = list(val) if isinstance(val, tuple) else [val]
                    else:
                        vals = val if isinstance(val, tuple) else (val,)
                        for k, vv in enumerate(vals):
                            acc[k] += vv
            row.append([a / (n * n) for a in acc])
        out.append(row)
    return out


def encode_rows(pixels, linear=True):
    rows = []
    for row in pixels:
        b = bytearray()
        for px in row:
            for v in px:
                b.append(srgb_encode(v) if linear else
                         int(round(min(max(v, 0.0), 1.0) * 255)))
        rows.append(bytes(b))
    return rows


# ---------------------------------------------------------------- gobos

def gobo_dots(u, v):
    """Polka dots on a hexagonal grid, white on black."""
    pitch = 1 / 6.0
    radius = 0.32 * pitch
    best = 1e9
    row = round(v / (pitch * math.sqrt(3) / 2))
    for r in (row - 1, row, row + 1):
        cy = r * pitch * math.sqrt(3) / 2
        off = 0.5 * pitch if r % 2 else 0.0
        col = round((u - off) / pitch)
        for c in (col - 1, col, col + 1):
            cx = c * pitch + off
            best = min(best, math.hypot(u - cx, v - cy))
    return 1.0 if best < radius else 0.0


def gobo_star(u, v):
    """A six-pointed star inside a thin ring, white on black."""
    x, y = u - 0.5, v - 0.5
    r = math.hypot(x, y)
    a = math.atan2(y, x)
    # Star: radius oscillates between inner and outer with 6 points.
    k = abs(((a * 6 / (2 * math.pi)) % 1.0) - 0.5) * 2  # 1 at points
    star_r = 0.15 + 0.24 * k
    if r < star_r and r > 0.05:
        return 1.0
    if 0.41 < r < 0.45:
        return 1.0
    return 0.0


# ---------------------------------------------------------------- terrain

def value_noise(rng, n):
    """A smooth value-noise function on [0, 1]^2 with an n x n lattice."""
    lattice = [[rng.random() for _ in range(n + 1)] for _ in range(n + 1)]

    def smooth(t):
        return t * t * (3 - 2 * t)

    def f(u, v):
        x, y = u * n, v * n
        i, j = min(int(x), n - 1), min(int(y), n - 1)
        fx, fy = smooth(x - i), smooth(y - j)
        a = lattice[j][i] + (lattice[j][i + 1] - lattice[j][i]) * fx
        b = lattice[j + 1][i] + (lattice[j + 1][i + 1] - lattice[j + 1][i]) * fx
        return a + (b - a) * fy
    return f


def height_grid(size, height):
    """A size x size grid of height(u, v) for u, v in [0, 1] (v down the
    image's rows), clamped at 0 and scaled so that the highest is 1."""
    rows = []
    for y in range(size):
        v = y / (size - 1)
        rows.append([max(height(x / (size - 1), v), 0.0) for x in range(size)])
    top = max(max(r) for r in rows)
    return [[[h / top] for h in r] for r in rows]


def make_terrain(size=128):
    """Heights in [0, 1]: a high mountain ridge running along x near the back
    (top of the image; image rows are z) whose crest is cut by narrow, deep
    notches that let low sunlight through, lower foothills in front of it, a
    flat valley at the bottom of the image, and some value noise."""
    rng = random.Random(8)
    n1, n2 = value_noise(rng, 5), value_noise(rng, 11)
    notches = [(0.18, 0.035), (0.41, 0.05), (0.63, 0.03), (0.84, 0.045)]

    def height(u, v):
        # The main ridge: a crest line that wanders, with notches.
        centre = 0.24 + 0.05 * math.sin(2 * math.pi * (u * 1.2 + 0.1))
        crest = 0.85 + 0.15 * math.sin(2 * math.pi * (u * 2.3 + 0.4))
        for nu, nw in notches:
            crest -= 0.62 * math.exp(-((u - nu) / nw) ** 2)
        h = crest * math.exp(-((v - centre) / 0.12) ** 2)
        # Foothills.
        fc = 0.5 + 0.03 * math.sin(2 * math.pi * (u * 2.0 + 0.3))
        fh = 0.28 + 0.1 * math.sin(2 * math.pi * (u * 3.1 + 0.7))
        h = max(h, fh * math.exp(-((v - fc) / 0.07) ** 2))
        h += (0.06 * n1(u, v) + 0.025 * n2(u, v)) * (1.2 - v)
        h *= 1.0 - 0.8 * max(v - 0.55, 0.0) / 0.45  # the valley in front
        return h
    return height_grid(size, height)


def make_valley(size=128):
    """Heights in [0, 1] of a valley running along z (image rows) between
    two side ridges, closed at the far end (the top of the image) by a
    cross ridge whose crest is cut by deep notches, through which a low sun
    beyond it shines down the valley; a gently rising floor and some value
    noise."""
    rng = random.Random(12)
    n1, n2 = value_noise(rng, 6), value_noise(rng, 13)
    notches = [(0.33, 0.035), (0.47, 0.025), (0.6, 0.045), (0.72, 0.03)]

    def height(u, v):
        crest = 0.8 + 0.06 * math.sin(2 * math.pi * (u * 1.7 + 0.2))
        for nu, nw in notches:
            crest -= 0.6 * math.exp(-((u - nu) / nw) ** 2)
        across = crest * math.exp(-((v - 0.1) / 0.07) ** 2)
        right = (0.9 + 0.1 * math.sin(2 * math.pi * (v * 1.3 + 0.1))) \
            * math.exp(-((u - 0.9) / 0.1) ** 2)
        left = (0.7 + 0.08 * math.sin(2 * math.pi * (v * 2.3 + 0.6))) \
            * math.exp(-((u - 0.08) / 0.1) ** 2)
        floor = 0.03 + 0.04 * (1.0 - v)
        return max(across, right, left, floor) + 0.05 * n1(u, v) + 0.02 * n2(u, v)
    return height_grid(size, height)


# ---------------------------------------------------------------- stained glass

def make_stained_glass(size=128):
    """Voronoi panes of saturated colours within a lead frame, RGB linear."""
    rng = random.Random(5)
    palette = [(0.80, 0.08, 0.06), (0.08, 0.22, 0.85), (0.95, 0.75, 0.08),
               (0.10, 0.65, 0.18), (0.55, 0.10, 0.70), (0.95, 0.40, 0.05),
               (0.15, 0.60, 0.80), (0.90, 0.85, 0.60)]
    seeds = []
    for j in range(4):
        for i in range(3):
            seeds.append(((i + 0.2 + 0.6 * rng.random()) / 3,
                          (j + 0.2 + 0.6 * rng.random()) / 4,
                          palette[rng.randrange(len(palette))]))
    lead = 0.012
    frame = 0.03
    mullion = 0.012

    def fn(u, v):
        if u < frame or u > 1 - frame or v < frame or v > 1 - frame:
            return (0.01, 0.01, 0.01)
        if abs(u - 0.5) < mullion:  # the central mullion
            return (0.01, 0.01, 0.01)
        d = sorted((math.hypot(u - sx, v - sy), c) for sx, sy, c in seeds)
        (d0, c0), (d1, _) = d[0], d[1]
        if d1 - d0 < 2 * lead:
            return (0.01, 0.01, 0.01)
        return c0
    return supersample(size, size, fn, n=3)


# ---------------------------------------------------------------- teapot

def catmull_rom(points, samples_per_segment):
    """Samples a Catmull-Rom spline through points (tuples), ends included."""
    pts = [points[0]] + list(points) + [points[-1]]
    out = []
    for s in range(1, len(pts) - 2):
        p0, p1, p2, p3 = pts[s - 1], pts[s], pts[s + 1], pts[s + 2]
        for k in range(samples_per_segment):
            t = k / samples_per_segment
            t2, t3 = t * t, t * t * t
            out.append(tuple(
                0.5 * (2 * b + (-a + c) * t + (2 * a - 5 * b + 4 * c - d) * t2
                       + (-a + 3 * b - 3 * c + d) * t3)
                for a, b, c, d in zip(p0, p1, p2, p3)))
    out.append(points[-1])
    return out


class Mesh:
    def __init__(self):
        self.v = []
        self.f = []

    def add_vertex(self, p):
        self.v.append(p)
        return len(self.v) - 1

    def add_part(self, verts, faces):
        base = len(self.v)
        self.v.extend(verts)
        self.f.extend([(a + base, b + base, c + base) for a, b, c in faces])


def signed_volume(verts, faces):
    vol = 0.0
    for a, b, c in faces:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = verts[a], verts[b], verts[c]
        vol += (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx)
                + az * (bx * cy - by * cx)) / 6.0
    return vol


def orient_outward(verts, faces):
    """Flips a closed part's faces if they wind inwards."""
    if signed_volume(verts, faces) < 0:
        return [(a, c, b) for a, b, c in faces]
    return faces


def lathe(profile, segments):
    """Revolves (r, y) points about the Y axis; the first and last points
    must have r = 0 (the poles). Returns a closed part."""
    verts, faces = [], []
    rings = []
    for r, y in profile:
        if r <= 1e-9:
            verts.append((0.0, y, 0.0))
            rings.append([len(verts) - 1] * segments)
            continue
        ring = []
        for k in range(segments):
            a = 2 * math.pi * k / segments
            verts.append((r * math.cos(a), y, r * math.sin(a)))
            ring.append(len(verts) - 1)
        rings.append(ring)
    for i in range(len(rings) - 1):
        r0, r1 = rings[i], rings[i + 1]
        for k in range(segments):
            k1 = (k + 1) % segments
            a, b, c, d = r0[k], r0[k1], r1[k1], r1[k]
            if a != b:
                faces.append((a, b, c))
            if c != d:
                faces.append((a, c, d))
    return verts, orient_outward(verts, faces)


def facing(verts, face, inside):
    """The dot product of a face's counter-clockwise normal with the vector
    from a point inside the part to the face: positive if it faces out."""
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = (verts[i] for i in face)
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    return (nx * (ax - inside[0]) + ny * (ay - inside[1])
            + nz * (az - inside[2]))


def sweep_tube(path, radii, sides):
    """A tube of circular sections along a path in the XY plane, with the
    given radius at each path point, capped at both ends: a closed part."""
    verts, faces = [], []
    rings = []
    n = len(path)
    for i, (px, py, pz) in enumerate(path):
        a = path[max(i - 1, 0)]
        b = path[min(i + 1, n - 1)]
        tx, ty = b[0] - a[0], b[1] - a[1]
        tl = math.hypot(tx, ty)
        tx, ty = tx / tl, ty / tl
        nx, ny = -ty, tx  # in-plane normal; the binormal is +Z
        ring = []
        for k in range(sides):
            ang = 2 * math.pi * k / sides
            c, s = math.cos(ang) * radii[i], math.sin(ang) * radii[i]
            verts.append((px + nx * c, py + ny * c, pz + s))
            ring.append(len(verts) - 1)
        rings.append(ring)
    for i in range(n - 1):
        r0, r1 = rings[i], rings[i + 1]
        for k in range(sides):
            k1 = (k + 1) % sides
            faces.append((r0[k], r0[k1], r1[k1]))
            faces.append((r0[k], r1[k1], r1[k]))
    # Make the sides face away from the path: test the first face against
    # the path point of its ring.
    if facing(verts, faces[0], path[0]) < 0:
        faces = [(a, c, b) for a, b, c in faces]
    # Cap each end with a fan about the path's end point, facing away from
    # the neighbouring path point (out of the tube).
    for ring, end, inner in ((rings[0], path[0], path[1]),
                             (rings[-1], path[-1], path[-2])):
        verts.append(end)
        centre = len(verts) - 1
        cap = [(centre, ring[(k + 1) % sides], ring[k]) for k in range(sides)]
        if facing(verts, cap[0], inner) < 0:
            cap = [(a, c, b) for a, b, c in cap]
        faces.extend(cap)
    assert signed_volume(verts, faces) > 0
    return verts, faces


def make_teapot():
    """A teapot standing on y = 0, about 3 wide (handle to spout tip) and 1.44
    high, the spout towards +X."""
    mesh = Mesh()
    # Body and lid as one surface of revolution, from the bottom centre up
    # the wall, over the rim, up the lid and over the knob to the top.
    body_ctrl = [(0.62, 0.0), (0.80, 0.06), (0.95, 0.25), (1.00, 0.45),
                 (0.92, 0.70), (0.75, 0.88), (0.68, 0.93)]
    lid_ctrl = [(0.68, 0.93), (0.66, 0.97), (0.50, 1.03), (0.25, 1.08),
                (0.12, 1.10)]
    knob_ctrl = [(0.12, 1.10), (0.10, 1.15), (0.18, 1.21), (0.15, 1.27),
                 (0.06, 1.30)]
    profile = [(0.0, 0.0)]
    profile += catmull_rom(body_ctrl, 4)
    profile += catmull_rom(lid_ctrl, 2)[1:]
    profile += catmull_rom(knob_ctrl, 2)[1:]
    profile += [(0.0, 1.305)]
    mesh.add_part(*lathe(profile, 48))

    # Spout: starts inside the body and rises out to +X, tapering.
    spout_ctrl = [(0.60, 0.30, 0.0), (0.95, 0.35, 0.0), (1.20, 0.55, 0.0),
                  (1.35, 0.85, 0.0), (1.50, 1.00, 0.0)]
    spout = catmull_rom(spout_ctrl, 6)
    n = len(spout)
    radii = [0.2 - 0.12 * (i / (n - 1)) ** 0.8 for i in range(n)]
    mesh.add_part(*sweep_tube(spout, radii, 16))

    # Handle: an arc on the -X side, both ends buried in the body.
    handle = []
    m = 24
    for i in range(m + 1):
        a = math.radians(75 + 230 * i / m)
        handle.append((-0.92 + 0.42 * math.cos(a) * 1.05,
                       0.50 + 0.34 * math.sin(a), 0.0))
    mesh.add_part(*sweep_tube(handle, [0.07] * len(handle), 12))
    # A little taller than modelled.
    mesh.v = [(x, 1.1 * y, z) for x, y, z in mesh.v]
    return mesh


def write_obj(path, mesh):
    with open(path, "w") as f:
        f.write("# Procedural teapot from tools/gen_assets.py: %d vertices, "
                "%d triangles,\n# counter-clockwise outward, y up, on y = 0.\n"
                % (len(mesh.v), len(mesh.f)))
        for x, y, z in mesh.v:
            f.write("v %.4f %.4f %.4f\n" % (x, y, z))
        for a, b, c in mesh.f:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))


# ---------------------------------------------------------------- main

def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        here, os.pardir, "scenes", "assets")
    out = os.path.normpath(out)
    os.makedirs(out, exist_ok=True)

    write_obj(os.path.join(out, "teapot.obj"), make_teapot())
    write_png(os.path.join(out, "gobo_dots.png"), 128, 128, 1,
              encode_rows(supersample(128, 128, gobo_dots)))
    write_png(os.path.join(out, "gobo_star.png"), 128, 128, 1,
              encode_rows(supersample(128, 128, gobo_star)))
    # Heights are data, not colour: stored as plain grey levels in a PNG
    # tagged linear (gAMA 1.0), so that readers take code / 255 as height.
    write_png(os.path.join(out, "terrain.png"), 128, 128, 1,
              encode_rows(make_terrain(128), linear=False), linear_data=True)
    write_png(os.path.join(out, "valley.png"), 128, 128, 1,
              encode_rows(make_valley(128), linear=False), linear_data=True)
    write_png(os.path.join(out, "stained_glass.png"), 128, 128, 3,
              encode_rows(make_stained_glass(128)))
    for name in sorted(os.listdir(out)):
        print("%s/%s" % (out, name))


if __name__ == "__main__":
    main()
