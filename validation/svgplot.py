"""The speed-against-error plot, written directly as SVG.

Time and error on logarithmic axes; one curve per renderer (its own Pareto
front, through all its settings' points, which are drawn as markers); the
Pareto front over all renderers marked by a thick grey line and rings; the
1%, 2% and 5% error levels dotted. Standalone SVG with no scripts and no
external resources, so the report works offline; every point has a tooltip
(an SVG <title>) naming its setting.
"""

import math
from xml.sax.saxutils import escape

from .metrics import fmt_percent, fmt_seconds, pareto_front

WIDTH, HEIGHT = 760, 440
LEFT, RIGHT, TOP, BOTTOM = 70, 230, 34, 52
FLOOR = 1e-6  # errors below this (identical images) are drawn at it
LEVELS = (0.01, 0.02, 0.05)


def _decades(lo, hi):
    """The powers of ten spanning [lo, hi], at least one decade apart."""
    a = math.floor(math.log10(lo))
    b = math.ceil(math.log10(hi))
    if b <= a:
        b = a + 1
    return a, b


# A series drawn dashed (a renderer's second timing: gl_shafts' first image).
_DASH = ' stroke-dasharray="5,3"'


def _decade(exp):
    """10^exp in fixed notation with thousands separators ("0.01", "1,000")."""
    return "{:,.{}f}".format(10.0 ** exp, max(0, -exp))


def _fmt_tick(exp, unit):
    if unit == "s":
        return "%s s" % _decade(exp) if exp >= 0 else "%s ms" % _decade(exp + 3)
    return "%s%%" % _decade(exp + 2)


def speed_error_svg(series, title):
    """The plot as SVG text. `series`: list of dicts with label, colour and
    points [(seconds, error, tooltip)], and optionally dashed (True: the
    line is dashed); points with None are skipped."""
    pts = [(t, max(e, FLOOR), tip) for s in series for (t, e, tip) in s["points"]
           if t is not None and e is not None and t > 0]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" '
           'viewBox="0 0 %d %d" font-family="sans-serif" font-size="12">'
           % (WIDTH, HEIGHT, WIDTH, HEIGHT),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="20" font-size="14" font-weight="bold">%s</text>'
           % (LEFT, escape(title))]
    pw, ph = WIDTH - LEFT - RIGHT, HEIGHT - TOP - BOTTOM
    if not pts:
        out.append('<text x="%d" y="%d">no rendering to plot</text>' % (LEFT + 20, TOP + ph // 2))
        out.append("</svg>")
        return "\n".join(out)
    tx0, tx1 = _decades(min(p[0] for p in pts), max(p[0] for p in pts))
    ey0, ey1 = _decades(min(min(p[1] for p in pts), min(LEVELS)),
                        max(max(p[1] for p in pts), max(LEVELS)))

    def X(t):
        return LEFT + pw * (math.log10(t) - tx0) / (tx1 - tx0)

    def Y(e):
        return TOP + ph * (1 - (math.log10(max(e, FLOOR)) - ey0) / (ey1 - ey0))

    # Grid and ticks.
    for k in range(tx0, tx1 + 1):
        x = X(10.0 ** k)
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' % (x, TOP, x, TOP + ph))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">%s</text>'
                   % (x, TOP + ph + 16, _fmt_tick(k, "s")))
    for k in range(ey0, ey1 + 1):
        y = Y(10.0 ** k)
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (LEFT, y, LEFT + pw, y))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%s</text>'
                   % (LEFT - 6, y + 4, _fmt_tick(k, "e")))
    for level in LEVELS:
        y = Y(level)
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#888" '
                   'stroke-dasharray="2,3"/>' % (LEFT, y, LEFT + pw, y))
        out.append('<text x="%d" y="%.1f" fill="#666" font-size="10">%g%%</text>'
                   % (LEFT + pw + 4, y + 3, level * 100))
    out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="none" stroke="#333"/>'
               % (LEFT, TOP, pw, ph))
    out.append('<text x="%d" y="%d" text-anchor="middle">render time (log)</text>'
               % (LEFT + pw // 2, HEIGHT - 12))
    out.append('<text transform="translate(16,%d) rotate(-90)" text-anchor="middle">'
               'relative RMS error, lit region (log)</text>' % (TOP + ph // 2))

    # The overall Pareto front under everything else.
    front = pareto_front(pts)
    if len(front) > 1:
        path = " ".join("%.1f,%.1f" % (X(t), Y(e)) for t, e, _ in front)
        out.append('<polyline points="%s" fill="none" stroke="#999" stroke-width="7" '
                   'stroke-opacity="0.45" stroke-linejoin="round"/>' % path)
    for t, e, tip in front:
        out.append('<circle cx="%.1f" cy="%.1f" r="8" fill="none" stroke="#555" '
                   'stroke-width="1.5"><title>Pareto front: %s</title></circle>'
                   % (X(t), Y(e), escape(tip)))

    # One curve per renderer: its own front, and every point.
    for s in series:
        own = [(t, max(e, FLOOR), tip) for (t, e, tip) in s["points"]
               if t is not None and e is not None and t > 0]
        if not own:
            continue
        f = pareto_front(own)
        if len(f) > 1:
            out.append('<polyline points="%s" fill="none" stroke="%s" stroke-width="2"%s/>'
                       % (" ".join("%.1f,%.1f" % (X(t), Y(e)) for t, e, _ in f), s["colour"],
                          _DASH if s.get("dashed") else ""))
        for t, e, tip in own:
            out.append('<circle cx="%.1f" cy="%.1f" r="3.5" fill="%s"><title>%s: %s, '
                       '%s, %s</title></circle>'
                       % (X(t), Y(e), s["colour"], escape(s["label"]), escape(tip),
                          escape(fmt_seconds(t)), escape(fmt_percent(e))))

    # Legend.
    ly = TOP + 8
    for s in series:
        if not any(t is not None and e is not None for t, e, _ in s["points"]):
            continue
        x = LEFT + pw + 34
        out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-width="2"%s/>'
                   % (x, ly, x + 18, ly, s["colour"], _DASH if s.get("dashed") else ""))
        out.append('<circle cx="%d" cy="%d" r="3.5" fill="%s"/>' % (x + 9, ly, s["colour"]))
        out.append('<text x="%d" y="%d">%s</text>' % (x + 24, ly + 4, escape(s["label"])))
        ly += 18
    x = LEFT + pw + 34
    out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="#999" stroke-width="7" '
               'stroke-opacity="0.45"/>' % (x, ly, x + 18, ly))
    out.append('<circle cx="%d" cy="%d" r="8" fill="none" stroke="#555"/>' % (x + 9, ly))
    out.append('<text x="%d" y="%d">Pareto front</text>' % (x + 24, ly + 4))
    out.append("</svg>")
    return "\n".join(out)
