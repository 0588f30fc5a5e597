"""The validation report: DIR/index.html and DIR/summary.md.

Both are made from the results dict that validate.py builds (and saves as
DIR/results.json). The HTML page shows, per scene, the images side by side
with their difference images, the speed-against-error plot, the table of
every run and the time each renderer needs to reach 1%, 2% and 5% error;
then the hard cases. It uses relative links only (images and SVG plots in
DIR), so it works offline and from a copy of DIR. summary.md holds the
numbers alone, for committing.
"""

import html
import os
from pathlib import Path

from .metrics import fmt_number, fmt_percent, fmt_seconds
from .verdicts import text as verdict_text

THRESHOLDS = (0.01, 0.02, 0.05)

# The key suffix of a renderer's warm-frame series (gl_shafts in-process)
# in a scene's time_to tables; the renderer's own key is its first image.
WARM = ":warm"

CSS = """
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 1400px; }
h1 { font-size: 1.6em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.9em; }
th, td { border: 1px solid #ddd; padding: 3px 7px; text-align: left; vertical-align: top; }
th { background: #f4f4f4; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
.strip { display: flex; flex-wrap: wrap; gap: 10px; }
.strip figure { margin: 0; font-size: 0.85em; width: 480px; }
.strip img { display: block; image-rendering: pixelated; width: 480px; height: auto; }
img.thumb { height: 96px; image-rendering: pixelated; display: block; }
.hover { position: relative; display: inline-block; }
.hover img.diff { position: absolute; top: 0; left: 0; opacity: 0; }
.hover:hover img.diff { opacity: 1; }
.fail { color: #b00; font-weight: bold; } .ok { color: #070; } .note { color: #666; }
.swatch { display: inline-block; width: 0.9em; height: 0.9em; margin-right: 4px; }
"""


def _e(text):
    return html.escape(str(text)) if text is not None else ""


def _rel(path, base):
    """A link from the report directory to a file inside it."""
    return os.path.relpath(path, base).replace(os.sep, "/")


def _num(v, fmt):
    """A number for tables; "n/a" when the comparison gave none (NaN or
    infinity in the image, which JSON writes as null)."""
    if v is None:
        return "n/a"
    return fmt(v) if callable(fmt) else fmt % v


def _time_of(run):
    """The time a run is judged by: the renderer's own, else the wall time."""
    t = run.get("tool_seconds")
    return t if t is not None else run.get("wall_seconds")


def series_label(rix, key, keys):
    """The label of a time_to key: the renderer's, and for a renderer timed
    both ways ("NAME" and "NAME:warm" among `keys`) which way."""
    base = key[:-len(WARM)] if key.endswith(WARM) else key
    label = rix[base]["label"] if base in rix else base
    if key.endswith(WARM):
        return label + ", warm frame"
    if base + WARM in keys:
        return label + ", first image"
    return label


def _times_text(run):
    """A run's time for captions: its own, and its warm frame if timed."""
    text = fmt_seconds(_time_of(run))
    if run.get("warm_seconds") is not None:
        text = "%s (first image), %s warm" % (text, fmt_seconds(run["warm_seconds"]))
    return text


def _failure_text(run):
    """Why a run has no figures: "not exported: REASON" where the exporter
    refuses the scene for the renderer, else "failed: ERROR"."""
    why = run.get("error") or run.get("compare_error") or ""
    return ("not exported: " if run.get("status") == "not_exported" else "failed: ") + why


def renderer_index(results):
    return {r["name"]: r for r in results["renderers"]}


def _best_runs(scene):
    """Per renderer, its run with the least error."""
    best = {}
    for run in scene.get("runs", []):
        m = run.get("metrics")
        if not m or m.get("rel_rms") is None:
            continue
        b = best.get(run["renderer"])
        if b is None or m["rel_rms"] < b["metrics"]["rel_rms"]:
            best[run["renderer"]] = run
    return best


def _figure(src, caption, base):
    return ('<figure><a href="%s"><img src="%s" alt="%s"></a><figcaption>%s</figcaption></figure>'
            % (_rel(src, base), _rel(src, base), _e(caption), caption))


def _thumb(src, base, diff=None):
    """A small image linking to itself; with `diff`, the pointer over it
    shows the difference image in its place."""
    if not src:
        return ""
    if diff:
        return _hover(src, diff, base, "thumb")
    return '<a href="%s"><img class="thumb" src="%s" alt=""></a>' % (_rel(src, base), _rel(src, base))


def _hover(src, diff, base, cls=""):
    """An image that shows its difference image while the pointer is over
    it (CSS only: the page stays static)."""
    return ('<a class="hover" href="%s" title="pointer over: the difference from the '
            'reference"><img class="%s" src="%s" alt=""><img class="diff %s" src="%s" '
            'alt=""></a>' % (_rel(src, base), cls, _rel(src, base), cls, _rel(diff, base)))


def _time_to_cells(tt):
    cells = []
    for th in THRESHOLDS:
        cells.append('<td class="num">%s</td>' % _e(fmt_seconds(tt.get("%g" % th))))
    best = tt.get("best")
    if best:
        cells.append('<td class="num">%s at %s</td>' % (_e(fmt_percent(best[0])), _e(fmt_seconds(best[1]))))
    else:
        cells.append("<td></td>")
    return "".join(cells)


def _header(results):
    m = results["machine"]
    out = ["<h1>Shafts validation report</h1>",
           "<p>Mode <b>%s</b>, %s; %s, %d CPU threads. This validation took %s (%d runs "
           "rendered, %d from the cache); from an empty cache its runs take %s of "
           "rendering.</p>" % (
               _e(results["mode"]), _e(results["date"]), _e(m.get("cpu", "unknown CPU")),
               m.get("threads", 0), _e(fmt_seconds(results.get("elapsed_seconds"))),
               results.get("rendered", 0), results.get("cached", 0),
               _e(fmt_seconds(results.get("render_seconds")))),
           "<p>Every image is compared with the converged reference (lmm_tracer "
           "<code>--mode reference</code> at %d spp, seed 0) in linear radiance: "
           "<b>error</b> is the relative RMS error over the lit region (pixels whose reference "
           "luminance exceeds %g of its largest), PSNR uses the reference's largest value as "
           "peak, <b>scale</b> is the image's summed luminance over the reference's on the lit "
           "region (1 when right on average). Times are the renderer's own figure where it "
           "reports one (else the wall time the validation measured): the plots and the "
           "summary use them. gl_shafts is timed both ways: its <b>first image</b> from the "
           "command line (shader compilation included: what a one-off user waits for) and "
           "its <b>warm frame</b> rendered in-process by gl_shafts_bench (the median of a few "
           "frames after a warm-up one: what a viewport or an animation pays per frame); the "
           "plots (warm frame solid, first image dashed) and the tables show both. "
           "The pointer over a rendering shows its difference image in its place. "
           "Difference images: red where the image is brighter than the "
           "reference, blue where darker, green for NaN, infinite or negative values; full "
           "intensity is a tenth of the reference's 99th-percentile luminance.</p>"
           % (results["reference_spp"], results["lit"])]
    return out


def _renderers_table(results):
    out = ["<h2 id=renderers>Renderers</h2>", "<table><tr><th>renderer</th><th>status</th>"
           "<th>version</th><th>what is run</th></tr>"]
    for r in results["renderers"]:
        status = ('<span class="ok">available</span>' if r["available"]
                  else '<span class="fail">skipped</span>: %s' % _e(r["note"]))
        out.append('<tr><td><span class="swatch" style="background:%s"></span>%s</td><td>%s</td>'
                   '<td><small>%s</small></td><td>%s</td></tr>'
                   % (r["colour"], _e(r["label"]), status, _e(r.get("version", "")), _e(r["about"])))
    out.append("</table>")
    return out


def _summary_table(results):
    rix = renderer_index(results)
    out = ["<h2 id=summary>Summary: time to reach 1%, 2% and 5% error</h2>",
           "<p>The least measured time among a renderer's settings whose error is at most the "
           "level (no interpolation); a dash: no setting reached it. <i>Least error</i> is the "
           "renderer's best and the time of that run. Where a light is in view, the same "
           "figures <i>away from the lights</i> leave out the pixels next to it (a square of "
           "5% of the image height around it), where the radiance grows without bound and a "
           "handful of pixels can decide the error alone.</p>",
           "<table><tr><th rowspan=2>scene</th><th rowspan=2>renderer</th>"
           "<th colspan=4>whole lit region</th><th colspan=4>away from the lights</th>"
           "<th rowspan=2>error is (docs/validation.md, bias or noise)</th></tr>"
           "<tr><th>1%</th><th>2%</th><th>5%</th><th>least error</th>"
           "<th>1%</th><th>2%</th><th>5%</th><th>least error</th></tr>"]
    for s in results["scenes"]:
        if s.get("error"):
            out.append('<tr><td><a href="#scene-%s">%s</a></td><td colspan=10 class="fail">%s</td></tr>'
                       % (_e(s["name"]), _e(s["name"]), _e(s["error"])))
            continue
        first = True
        for name, tt in s["time_to"].items():
            masked = s.get("time_to_masked", {}).get(name)
            out.append("<tr><td>%s</td><td>%s</td>%s%s<td>%s</td></tr>" % (
                '<a href="#scene-%s">%s</a>' % (_e(s["name"]), _e(s["name"])) if first else "",
                _e(series_label(rix, name, s["time_to"])), _time_to_cells(tt),
                _time_to_cells(masked) if masked else '<td colspan=4 class="note">no light in view</td>',
                _e(_verdict_of(s, name))))
            first = False
        for name, why in s.get("not_exported", {}).items():
            out.append('<tr><td>%s</td><td>%s</td><td colspan=9 class="note">not exported: %s'
                       '</td></tr>' % ("" if not first else '<a href="#scene-%s">%s</a>'
                                       % (_e(s["name"]), _e(s["name"])),
                                       _e(rix[name]["label"]), _e(why)))
            first = False
    out.append("</table>")
    return out


def _scene_section(s, results, base):
    rix = renderer_index(results)
    out = ['<h2 id="scene-%s">%s</h2>' % (_e(s["name"]), _e(s["name"]))]
    if s.get("error"):
        out.append('<p class="fail">%s</p>' % _e(s["error"]))
        return out
    ref = s["reference"]
    out.append("<p><code>%s</code>, rendered at %d x %d%s. Reference: %s in %s.</p>"
               % (_e(s["source"]), s["width"], s["height"],
                  "" if s["has_medium"] else " (no medium: surfaces only; the sweeps over "
                  "medium settings are left out)",
                  _e(ref["label"]), _e(fmt_seconds(ref.get("tool_seconds")))))
    out += ["<p>%s</p>" % _e(t) for t in _twin_lines(s)]
    if s.get("self_check") is not None:
        out.append('<p class="note">Reference self-check: lmm_tracer at %d spp (another seed) '
                   'differs from it by %s; the reference, with %dx the samples, is closer '
                   'than that to the converged image.</p>'
                   % (s["self_check_spp"], _e(fmt_percent(s["self_check"])),
                      results["reference_spp"] // max(1, s["self_check_spp"])))
    # Side by side: the reference, then each renderer's best run and its difference.
    figs = [_figure(ref["png"], "reference", base)]
    for name, run in _best_runs(s).items():
        cap = "%s, %s: %s in %s" % (_e(rix[name]["label"]), _e(run["label"]),
                                    _e(fmt_percent(run["metrics"]["rel_rms"])),
                                    _e(_times_text(run)))
        figs.append('<figure>%s<figcaption>%s (least error; the pointer over the image '
                    'shows <a href="%s">its difference</a>)</figcaption></figure>'
                    % (_hover(run["png"], run["diff_png"], base), cap,
                       _rel(run["diff_png"], base)))
    out.append('<div class="strip">%s</div>' % "".join(figs))
    plots = '<img src="%s" alt="speed against error, %s">' % (_rel(s["plot"], base), _e(s["name"]))
    if s.get("plot_masked"):
        plots += ' <img src="%s" alt="speed against error away from the lights, %s">' % (
            _rel(s["plot_masked"], base), _e(s["name"]))
        out.append('<p class="note">A light is in view: %d pixels next to it are left out of '
                   'the figures <i>away from the lights</i> (right-hand plot).</p>'
                   % s.get("masked_pixels", 0))
    out.append("<p>%s</p>" % plots)
    masked = s.get("time_to_masked")
    out.append("<table><tr><th>renderer</th><th>1%%</th><th>2%%</th><th>5%%</th><th>least error</th>%s</tr>"
               % ("<th>1%, away from lights</th><th>2%</th><th>5%</th><th>least error</th>" if masked else ""))
    for name, tt in s["time_to"].items():
        out.append("<tr><td>%s</td>%s%s</tr>" % (_e(series_label(rix, name, s["time_to"])),
                                                 _time_to_cells(tt),
                                                 _time_to_cells(masked[name]) if masked else ""))
    out.append("</table>")
    out.append("<table><tr><th>renderer</th><th>setting</th><th>time</th><th>warm frame</th>"
               "<th>wall</th><th>error</th>%s"
               "<th>mean rel.</th><th>PSNR</th><th>max abs.</th><th>scale</th><th>bad</th>"
               "<th>image</th><th>difference</th></tr>"
               % ("<th>error away from lights</th>" if masked else ""))
    for run in s["runs"]:
        label = _e(rix[run["renderer"]]["label"])
        if run["status"] != "ok" or not run.get("metrics"):
            out.append('<tr><td>%s</td><td>%s</td><td colspan=%d class="%s">%s</td></tr>'
                       % (label, _e(run["label"]), 12 if masked else 11,
                          "note" if run["status"] == "not_exported" else "fail",
                          _e(_failure_text(run))))
            continue
        m = run["metrics"]
        mm = run.get("metrics_masked")
        out.append("<tr><td>%s</td><td>%s%s</td><td class=num>%s</td><td class=num>%s</td>"
                   "<td class=num>%s</td>"
                   "<td class=num>%s</td>%s<td class=num>%s</td><td class=num>%s</td>"
                   "<td class=num>%s</td><td class=num>%s</td><td class=num>%s</td>"
                   "<td>%s</td><td>%s</td></tr>" % (
                       label, _e(run["label"]), ' <span class="note">(cached)</span>' if run.get("cached") else "",
                       _e(fmt_seconds(run.get("tool_seconds"))),
                       _e(fmt_seconds(run.get("warm_seconds")) if run.get("warm_seconds") is not None
                          else ""),
                       _e(fmt_seconds(run.get("wall_seconds"))),
                       _e(fmt_percent(m["rel_rms"])),
                       "<td class=num>%s</td>" % _e(fmt_percent(mm["rel_rms"])) if masked and mm
                       else ("<td></td>" if masked else ""),
                       _e(fmt_percent(m["mean_rel"])),
                       "%.1f dB" % m["psnr"] if m.get("psnr") is not None else "identical",
                       _num(m.get("max_abs"), fmt_number), _num(m.get("scale"), "%.4f"),
                       '<span class="fail">%d</span>' % m["bad_values"] if m["bad_values"] else "0",
                       _thumb(run.get("png"), base, run.get("diff_png")),
                       _thumb(run.get("diff_png"), base)))
    out.append("</table>")
    return out


def _verdict_of(s, key):
    """The bias-or-noise cell of a time_to key (verdicts.py): the
    renderer's verdict, on the first of its rows only (a renderer timed
    both ways has the same images, so the same errors, in both)."""
    base = key[:-len(WARM)] if key.endswith(WARM) else key
    first = next(k for k in s["time_to"] if k in (base, base + WARM))
    return verdict_text(s.get("verdicts", {}).get(base)) if key == first else ""


def _twin_lines(s):
    """What the report says about a scene's twin (twins.py), or about the
    scene a twin is made from."""
    if s.get("twin_of"):
        return ["Twin of %s: %s." % (s["twin_of"], "; ".join(s.get("changes", [])))]
    t = s.get("twin")
    if not t:
        return []
    shift = (" Its reference differs from this one by %s: what the changes alone do."
             % fmt_percent(t["shift"])) if t.get("shift") is not None else ""
    return ["Twin: %s: %s.%s" % (t["name"], "; ".join(t["changes"]), shift)]


def _check_text(chk):
    text = _check_value(chk)
    if chk.get("known_failure"):
        text += ' <span class="fail">known failure</span>: %s' % _e(chk["known"])
    elif chk.get("known"):
        text += ' <span class="ok">passes now: the known issue (%s) looks fixed</span>' % _e(chk["known"])
    return text


def _check_value(chk):
    if chk.get("value") is None:
        return _e(chk.get("note") or "")
    if chk["name"] == "finite, non-negative":
        return "%d bad values" % chk["value"]
    bound = chk.get("bound")
    return "%s%s" % (_e(fmt_percent(chk["value"])),
                     " (bound %s)" % _e(fmt_percent(bound)) if bound is not None else
                     ' <span class="note">(not bounded)</span>')


def _hard_section(hc, results, base):
    rix = renderer_index(results)
    out = ["<h2 id=hard>Hard cases</h2>"]
    if hc is None:
        out.append("<p>Not run (--no-hard-cases).</p>")
        return out
    out.append("<p>Generated scenes that push single scattering where it is hard "
               "(validation/hard/). Every rendering must hold no NaN, infinite or "
               "negative value anywhere; its error against the reference (lmm_tracer, %d spp), "
               "with the pixels next to a light in view masked out, must stay within the bound "
               "stated for the renderer and case; invariant pairs must agree. Renderers: %s.</p>"
               % (hc["reference_spp"], _e(", ".join(rix[n]["label"] for n in hc["renderers"]))))
    fails = hc.get("failures", [])
    known = hc.get("known_failures", [])
    out.append('<p class="%s">%d renderings, %d failed checks%s.</p>'
               % ("fail" if fails else "ok", sum(len(c["renderings"]) for c in hc["cases"]), len(fails),
                  ", %d known failures (reported to the renderer's owners)" % len(known) if known else ""))
    for f in fails:
        out.append('<p class="fail">FAIL: %s / %s %s: %s: %s</p>' % tuple(_e(x) for x in f))
    if hc.get("bounds"):
        out.append("<table><tr><th>renderer</th><th>setting kind</th><th>case</th><th>bound</th>"
                   "<th>why</th></tr>")
        for b in hc["bounds"]:
            out.append("<tr><td>%s</td><td>%s</td><td>%s</td><td class=num>%s</td><td>%s</td></tr>"
                       % (_e(b["renderer"]), _e(b["kind"]), _e(b["case"]), _e(b["bound"]), _e(b["why"])))
        out.append("</table>")
    for c in hc["cases"]:
        out.append("<h3>%s</h3><p>%s (%d x %d%s%s)</p>" % (
            _e(c["name"]), _e(c["description"]), c["width"], c["height"],
            ", %d pixels masked next to lights" % c["masked_pixels"] if c["masked_pixels"] else "",
            "; judged against the reference of %s, whose image it must equal" % _e(c["reference_case"])
            if c.get("reference_case") else ""))
        if c.get("error"):
            out.append('<p class="fail">%s</p>' % _e(c["error"]))
            continue
        for sk in c.get("skipped", []):
            out.append("<p>Not rendered by %s: %s.</p>" % (_e(rix[sk["renderer"]]["label"]),
                                                          _e(sk["why"])))
        out.append("<table><tr><th>renderer</th><th>setting</th><th>result</th><th>stability</th>"
                   "<th>error</th><th>invariance</th><th>time</th><th>image</th><th>difference</th></tr>")
        if c["reference"].get("png"):
            out.append('<tr><td>reference</td><td>lmm_tracer, %d spp</td><td></td><td></td><td></td>'
                       '<td></td><td class=num>%s</td><td>%s</td><td></td></tr>'
                       % (hc["reference_spp"], _e(fmt_seconds(c["reference"].get("seconds"))),
                          _thumb(c["reference"]["png"], base)))
        for r in c["renderings"]:
            checks = {k["name"]: k for k in r["checks"]}
            stab = checks.get("finite, non-negative")
            err = checks.get("error")
            inv = [k for k in r["checks"] if k["name"].startswith("equals")]
            other = [k for k in r["checks"] if k["name"] in ("renders", "compares", "input")]
            res = '<span class="ok">pass</span>' if r.get("ok") else '<span class="fail">FAIL</span>'
            out.append("<tr><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td><td>%s</td>"
                       "<td class=num>%s</td><td>%s</td><td>%s</td></tr>" % (
                           _e(rix[r["renderer"]]["label"]), _e(r["label"]), res,
                           _check_text(stab) if stab else _e("; ".join(k.get("note") or "" for k in other)),
                           _check_text(err) if err else "",
                           "<br>".join("%s: %s" % (_e(k["name"]), _check_text(k)) for k in inv),
                           _e(fmt_seconds(r.get("seconds"))),
                           _thumb(r.get("png"), base, r.get("diff_png")),
                           _thumb(r.get("diff_png"), base)))
        out.append("</table>")
    return out


def write_html(results, report_dir):
    """Writes report_dir/index.html."""
    base = Path(report_dir)
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
             "<title>Shafts validation (%s)</title><style>%s</style></head><body>"
             % (_e(results["mode"]), CSS)]
    parts += _header(results)
    toc = ['<a href="#renderers">renderers</a>', '<a href="#summary">summary</a>']
    toc += ['<a href="#scene-%s">%s</a>' % (_e(s["name"]), _e(s["name"])) for s in results["scenes"]]
    toc.append('<a href="#hard">hard cases</a>')
    parts.append("<p>Contents: %s</p>" % " · ".join(toc))
    parts += _renderers_table(results)
    parts += _summary_table(results)
    for s in results["scenes"]:
        parts += _scene_section(s, results, base)
    parts += _hard_section(results.get("hard_cases"), results, base)
    parts.append("</body></html>")
    text = "\n".join(parts) + "\n"
    tmp = base / ".index.html.tmp"
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, base / "index.html")


def summary_markdown(results):
    """The numbers of the report as Markdown (no images)."""
    rix = renderer_index(results)
    m = results["machine"]
    out = ["# Validation summary (%s mode)" % results["mode"], "",
           "Written by `python3 -m validation.validate --%s` on %s (%s, %d CPU threads; its runs "
           "take %s of rendering from an empty cache; this one took %s with %d runs "
           "rendered and %d from the cache). Errors are relative RMS over the lit region "
           "against lmm_tracer's reference at %d spp; times are the renderers' own, "
           "gl_shafts' both ways: its first image from the command line and its warm "
           "in-process frame (docs/validation.md)."
           % (results["mode"], results["date"], m.get("cpu", "unknown CPU"), m.get("threads", 0),
              fmt_seconds(results.get("render_seconds")),
              fmt_seconds(results.get("elapsed_seconds")), results.get("rendered", 0),
              results.get("cached", 0), results["reference_spp"]), ""]
    if results.get("command"):
        out += ["Command: `%s`%s." % (results["command"], ", at %s" % results["commit"]
                                      if results.get("commit") else ""), ""]
    out += ["## Renderers", "", "| renderer | status | version |", "|---|---|---|"]
    for r in results["renderers"]:
        out.append("| %s | %s | %s |" % (r["label"], "available" if r["available"]
                                          else "skipped: " + r["note"],
                                          (r.get("version") or "").replace("|", "/")))
    out += ["", "## Time to reach 1%, 2% and 5% error", "",
            "The least measured time among a renderer's settings whose relative RMS error "
            "over the lit region is at most the level. Where a light is in view, the "
            "figures in brackets leave out the pixels next to it (a square of 5% of the "
            "image height), where the radiance grows without bound. *Error is*: whether "
            "the renderer's remaining error is bias (more samples do not remove it) or "
            "noise, from how it falls over the sweep (the bracketed figures where a light "
            "is in view); a row with bias names its cause (docs/validation.md, \"Bias or "
            "noise\"). A scene's twin (NAME-hg, -lambert) is the scene with the phase and "
            "highlights Cycles and EEVEE represent exactly.", "",
            "| scene | size | renderer | 1% | 2% | 5% | least error (time) | error is |",
            "|---|---|---|---:|---:|---:|---:|---|"]
    for s in results["scenes"]:
        if s.get("error"):
            out.append("| %s | | | | | | %s | |" % (s["name"], s["error"]))
            continue
        for name, tt in s["time_to"].items():
            masked = s.get("time_to_masked", {}).get(name)

            def cell(th, tt=tt, masked=masked):
                text = fmt_seconds(tt.get("%g" % th))
                return text + (" (%s)" % fmt_seconds(masked.get("%g" % th)) if masked else "")

            def best_text(tt):
                b = tt.get("best") if tt else None
                return "%s (%s)" % (fmt_percent(b[0]), fmt_seconds(b[1])) if b else "–"
            out.append("| %s | %dx%d | %s | %s | %s | %s | %s | %s |" % (
                s["name"], s["width"], s["height"], series_label(rix, name, s["time_to"]),
                *[cell(th) for th in THRESHOLDS],
                best_text(tt) + (" [%s]" % best_text(masked) if masked else ""),
                _verdict_of(s, name).replace("|", "/")))
        for name, why in s.get("not_exported", {}).items():
            out.append("| %s | %dx%d | %s | | | | – | not exported: %s |" % (
                s["name"], s["width"], s["height"], rix[name]["label"],
                (why or "").replace("|", "/")))
    out += ["", "## Every run", ""]
    for s in results["scenes"]:
        if s.get("error"):
            continue
        plots = "![speed against error](plots/%s)" % os.path.basename(s["plot"])
        if s.get("plot_masked"):
            plots += " ![away from the lights](plots/%s)" % os.path.basename(s["plot_masked"])
        out += ["### %s" % s["name"], ""] + [t + "\n" for t in _twin_lines(s)]
        out += ["Reference: %s, %s." % (s["reference"]["label"],
                                        fmt_seconds(s["reference"].get("tool_seconds"))), "",
                plots, "",
                "| renderer | setting | time | warm frame | error | away from lights | PSNR "
                "| max abs. | scale |",
                "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
        for run in s["runs"]:
            mm = run.get("metrics")
            if run["status"] != "ok" or not mm:
                out.append("| %s | %s | %s | | | | | | |" % (
                    rix[run["renderer"]]["label"], run["label"],
                    _failure_text(run).replace("|", "/")[:200]))
                continue
            masked = run.get("metrics_masked")
            out.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                rix[run["renderer"]]["label"], run["label"], fmt_seconds(_time_of(run)),
                fmt_seconds(run["warm_seconds"]) if run.get("warm_seconds") is not None else "",
                fmt_percent(mm["rel_rms"]), fmt_percent(masked["rel_rms"]) if masked else "",
                "%.1f dB" % mm["psnr"] if mm.get("psnr") is not None else "identical",
                _num(mm.get("max_abs"), fmt_number), _num(mm.get("scale"), "%.3f")))
        out.append("")
    hc = results.get("hard_cases")
    if hc:
        out += ["## Hard cases", "",
                "%d renderings, %d failed checks, %d known failures (reference: lmm_tracer "
                "at %d spp)." % (sum(len(c["renderings"]) for c in hc["cases"]),
                                 len(hc.get("failures", [])), len(hc.get("known_failures", [])),
                                 hc["reference_spp"]), ""]
        out += ["- known failure: %s / %s %s: %s: %s" % tuple(f) for f in hc.get("known_failures", [])]
        out += ["",
                "| case | renderer | setting | result | error (bound) | invariance |",
                "|---|---|---|---|---|---|"]
        for c in hc["cases"]:
            if c.get("error"):
                out.append("| %s | | | %s | | |" % (c["name"], c["error"]))
            for sk in c.get("skipped", []):
                out.append("| %s | %s | | not rendered | %s | |" % (
                    c["name"], rix[sk["renderer"]]["label"], sk["why"]))
            for r in c["renderings"]:
                checks = {k["name"]: k for k in r["checks"]}
                err = checks.get("error")
                inv = [k for k in r["checks"] if k["name"].startswith("equals")]
                errtext = ""
                if err and err.get("value") is not None:
                    errtext = "%s (%s)" % (fmt_percent(err["value"]),
                                           fmt_percent(err["bound"]) if err.get("bound") is not None
                                           else "not bounded")
                elif not r.get("ok"):
                    errtext = "; ".join((k.get("note") or "") for k in r["checks"] if not k["ok"])[:200]
                known = any(k.get("known_failure") for k in r["checks"])
                out.append("| %s | %s | %s | %s | %s | %s |" % (
                    c["name"], rix[r["renderer"]]["label"], r["label"],
                    ("known failure" if known else "pass") if r.get("ok") else "**FAIL**",
                    errtext.replace("|", "/"),
                    "; ".join("%s: %s" % (k["name"], fmt_percent(k.get("value"))) for k in inv)))
        out.append("")
    return "\n".join(out) + "\n"
