"""Errors against the reference, and what the report derives from them.

The figures themselves come from shafts_compare (sh_image_compare in the
core library): relative RMS error over the lit region, mean relative error,
PSNR, the largest absolute error, the count of bad values (NaN, infinite,
negative) and the lit-region brightness ratio. This module calls it and
derives the speed-against-error summaries: each renderer's Pareto front and
the time it needs to reach a given error.
"""

import json
import math
import re
import subprocess


class CompareFailed(Exception):
    """shafts_compare could not compare the images (size, unreadable)."""


def compare(tool, ref, img, lit=0.01, diff=None, preview=None, exposure=0.0,
            diff_gain=10.0):
    """Runs shafts_compare on two images; returns its JSON figures as a
    dict (psnr None for identical images). Writes the difference and
    preview PNGs when their paths are given."""
    cmd = [str(tool), str(ref), str(img), "--json", "--lit", repr(lit)]
    if diff:
        cmd += ["--diff", str(diff), "--diff-gain", repr(diff_gain)]
    if preview:
        cmd += ["--preview", str(preview), "--exposure", repr(exposure)]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          check=False)
    if proc.returncode != 0:
        raise CompareFailed(proc.stderr.decode(errors="replace").strip()
                            or "shafts_compare exited with %d" % proc.returncode)
    return json.loads(proc.stdout)


def image_size(path):
    """(width, height) of an image file, from `oiiotool --info`. Raises
    subprocess.CalledProcessError if oiiotool fails or names no size."""
    info = subprocess.run(["oiiotool", "--info", str(path)], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, check=True, text=True).stdout
    m = re.search(r":\s*(\d+)\s*x\s*(\d+)", info)
    if not m:
        raise subprocess.CalledProcessError(1, ["oiiotool", "--info", str(path)], info)
    return int(m.group(1)), int(m.group(2))


def mask_image(src, rects, dst):
    """A copy of an image with the pixel rectangles (x, y, w, h) set to
    black, through oiiotool; `src` itself when there is nothing to mask.
    Raises subprocess.CalledProcessError if oiiotool fails."""
    if not rects:
        return src
    cmd = ["oiiotool", str(src)]
    for x, y, w, h in rects:
        cmd += ["--fill:color=0,0,0", "%dx%d+%d+%d" % (w, h, x, y)]
    cmd += ["-d", "float", "-o", str(dst)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return dst


def pareto_front(points):
    """The points no other point beats in both time and error (lower is
    better in both), sorted by time. `points` are (time, error, ...)
    tuples; points with a missing time or error are ignored."""
    pts = sorted((p for p in points if p[0] is not None and p[1] is not None),
                 key=lambda p: (p[0], p[1]))
    front, best = [], float("inf")
    for p in pts:
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def time_to_reach(points, threshold):
    """The least time of the points whose error is at most `threshold`
    (measured, not interpolated), or None if no point reaches it."""
    times = [p[0] for p in points
             if p[0] is not None and p[1] is not None and p[1] <= threshold]
    return min(times) if times else None


def _sig(x, digits):
    """x (positive) with `digits` significant digits, in fixed notation:
    never an exponent ("0.0012", "180", "12,300")."""
    x = float("%.*g" % (digits, x))  # rounded first: 0.9997 is 1.00
    decimals = max(0, digits - 1 - int(math.floor(math.log10(x))))
    return "{:,.{}f}".format(x, decimals)


def fmt_number(x):
    """A quantity (radiance) for people: 3 significant digits in fixed
    notation ("0.0725", "21.1", "1,230"), never an exponent."""
    if x is None:
        return "–"
    if x == 0:
        return "0"
    if abs(x) < 1e-6:
        return "< 0.000001"
    return ("-" if x < 0 else "") + _sig(abs(x), 3)


def fmt_seconds(t):
    """A time for people: 3 significant digits, in ms below a second, s
    below ten minutes, then minutes and hours ("12.3 ms", "1.50 s",
    "20.5 min")."""
    if t is None:
        return "–"
    if t <= 0:
        return "0 s"
    if t < 0.0009995:
        return "%s µs" % _sig(t * 1e6, 3) if t >= 1e-6 else "< 1 µs"
    if t < 0.9995:
        return "%s ms" % _sig(t * 1000, 3)
    if t < 599.5:
        return "%s s" % _sig(t, 3)
    if t < 7200:
        return "%.1f min" % (t / 60)
    return "%.1f h" % (t / 3600)


def fmt_percent(e):
    """A relative error (0.018 for 1.8%) for people: two significant digits
    below 10%, whole per cent above, never an exponent ("0.27 %", "1.8 %",
    "35 %", "180 %", "12,300 %"); "< 0.01 %" below that."""
    if e is None:
        return "–"
    p = abs(e) * 100
    if p == 0:
        return "0 %"
    if p < 0.01:
        return "< 0.01 %"
    if p < 9.95:
        return "%s %%" % _sig(p, 2)
    if p < 1e6:
        return "{:,.0f} %".format(p)
    return "> 1,000,000 %"
