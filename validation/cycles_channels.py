"""Cycles 3.4 and media whose coefficients differ between colour channels:
the exported script's one render (--one-pass, what Cycles itself does)
against its default, one pass per channel with grey coefficients (channel
c of pass c), each channel against the reference's.

  python3 -m validation.cycles_channels [--build-dir DIR] [--cache DIR]
      [--scenes a,b] [--samples N] [--seeds 1,2] [--ref-spp N] [--without PARTS]

For each scene (validation/peers.py's test scenes; by default the two
atmosphere rows; --without mie,ozone drops those parts of the air) and each of the two ways, at each seed: per channel, the
mean relative difference from the reference's channel over the lit region
and the ratio of their sums, over the whole image and over the top third of
its rows (on sky_sunset the sky far from the sun, lit mostly by Rayleigh);
then the two seeds' difference per channel, the noise those figures are
measured against; s/render is the wall time of the render command (all
three passes, Blender's start-up included). Every image goes through the run cache (runs.py), so a
second run costs only the comparisons. The figures of docs/scene_export.md,
"The atmosphere in Cycles", come from this script.
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

from . import renderers
from .metrics import CompareFailed, compare, image_size
from .peers import TESTDATA, Peers
from .runs import RunCache
from .scenes import prepare_file

CHANNELS = ("R", "G", "B")
WAYS = (("one pass", True), ("per channel", False))


def channel_image(src, c, dst, rows=None):
    """Channel c of the image `src` as a grey RGB image (written to dst),
    only its rows [0, rows) when rows is given; returns dst."""
    ch = CHANNELS[c]
    cmd = ["oiiotool", str(src), "--ch", "R=%s,G=%s,B=%s" % (ch, ch, ch)]
    if rows is not None:
        cmd += ["--cut", "%dx%d+0+0" % (image_size(src)[0], rows)]
    cmd += ["-d", "float", "-o", str(dst)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return dst


def figures(tool, ref, img, tmp, tag, rows):
    """{channel: (mean_rel, ratio, top rows' ratio)} of img against ref."""
    out = {}
    for c, name in enumerate(CHANNELS):
        whole = compare(tool, channel_image(ref, c, tmp / ("ref%s.exr" % name)),
                        channel_image(img, c, tmp / ("%s%s.exr" % (tag, name))))
        top = compare(tool, channel_image(ref, c, tmp / ("reft%s.exr" % name), rows),
                      channel_image(img, c, tmp / ("%st%s.exr" % (tag, name)), rows))
        out[name] = (whole["mean_rel"], whole["scale"], top["scale"])
    return out


def noise(tool, a, b, tmp):
    """{channel: mean_rel of image b against image a} (two seeds)."""
    return {name: compare(tool, channel_image(a, c, tmp / ("na%s.exr" % name)),
                          channel_image(b, c, tmp / ("nb%s.exr" % name)))["mean_rel"]
            for c, name in enumerate(CHANNELS)}


def parse(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build-dir", default=str(Path(__file__).resolve().parent.parent / "build"))
    ap.add_argument("--cache", help="the run cache (default: BUILD/validation-cache)")
    ap.add_argument("--scenes", default="atmosphere_sunset_small,atmosphere_space_small")
    ap.add_argument("--samples", type=int, default=128)
    ap.add_argument("--seeds", default="1,2")
    ap.add_argument("--ref-spp", type=int, default=1024)
    ap.add_argument("--without", default="",
                    help="comma-separated parts of the atmosphere (mie, ozone) to drop "
                         "from the scenes, to see which part an error comes with")
    return ap.parse_args(argv)


def scene_file(name, without, work):
    """The test scene `name`, or a copy without the atmosphere's parts
    `without` written into `work` (named NAME_without_PARTS.json)."""
    path = TESTDATA / (name + ".json")
    if not without:
        return path
    data = json.loads(path.read_text())
    for part in without:
        data["medium"].pop(part, None)
    out = Path(work) / ("%s_without_%s.json" % (name, "_".join(without)))
    out.write_text(json.dumps(data))
    return out


def main(argv=None):
    args = parse(argv)
    root = Path(__file__).resolve().parent.parent
    ctx = renderers.Context(root, args.build_dir, mode="quick", say=lambda m: None)
    cycles = renderers.by_name("cycles")[0]
    for adapter in (renderers.REFERENCE, cycles):
        note = adapter.missing(ctx)
        if note:
            print("cycles_channels: %s: %s" % (adapter.name, note), file=sys.stderr)
            return 2
    tool = ctx.tool("validation/shafts_compare")
    cache = RunCache(Path(args.cache) if args.cache else ctx.build / "validation-cache")
    peers = Peers(ctx, cache, args.ref_spp, lambda m: print(m, flush=True))
    seeds = [int(s) for s in args.seeds.split(",")]
    without = sorted(filter(None, args.without.split(",")))
    print("| scene | way | seed | channel | mean rel. diff. | ratio | ratio, top third "
          "| 2-seed noise | s/render |")
    print("|---|---|---|---|---|---|---|---|---|")
    try:
        for name in filter(None, args.scenes.split(",")):
            scene = prepare_file(scene_file(name, without, cache.root), cache.root)
            ref = peers.image(renderers.REFERENCE, scene, peers.ref_params,
                              "reference")["image"]
            with tempfile.TemporaryDirectory(prefix="cycles_channels_") as d:
                tmp = Path(d)
                rows = max(1, image_size(ref)[1] // 3)
                for way, one_pass in WAYS:
                    images, seconds = [], []
                    for s in seeds:
                        params = {"samples": args.samples, "seed": s}
                        if one_pass:
                            params["one_pass"] = True
                        run = peers.image(cycles, scene, params, "%d spp, seed %d, %s"
                                          % (args.samples, s, way))
                        images.append(run["image"])
                        seconds.append(run.get("wall_seconds") or 0.0)
                    n = noise(tool, images[0], images[1], tmp) if len(images) > 1 else {}
                    for s, img, sec in zip(seeds, images, seconds):
                        for ch, (mean, ratio, top) in figures(tool, ref, img, tmp, "i",
                                                              rows).items():
                            print("| %s | %s | %d | %s | %.4f | %.4f | %.4f | %s | %.1f |" % (
                                scene.name, way, s, ch, mean, ratio, top,
                                "%.4f" % n[ch] if ch in n else "-", sec), flush=True)
    except (CompareFailed, subprocess.CalledProcessError) as e:
        print("cycles_channels: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
