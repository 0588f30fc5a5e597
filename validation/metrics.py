"""Errors against the reference, and what the report derives from them.

The figures themselves come from shafts_compare (sh_image_compare in the
core library): relative RMS error over the lit region, mean relative error,
PSNR, the largest absolute error, the count of bad values (NaN, infinite,
negative) and the lit-region brightness ratio. This module calls it and
derives the speed-against-error summaries: each renderer's Pareto front and
the time it needs to reach a given error.
"""

import json
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


def fmt_seconds(t):
    """A time for tables: 3 significant digits, ms below a second."""
    if t is None:
        return "–"
    if t < 1:
        return "%.3g ms" % (t * 1000)
    if t < 600:
        return "%.3g s" % t
    return "%.1f min" % (t / 60)


def fmt_percent(e):
    """A relative error for tables."""
    if e is None:
        return "–"
    return "%.2g %%" % (e * 100)
