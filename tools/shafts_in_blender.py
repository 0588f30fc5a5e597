"""What happens when libshafts.so is loaded inside Blender's process
(docs/api.md, "Inside Blender"): run by Blender, it imports shafts.py,
loads the library, and compares the shared libraries mapped into the
process (/proc/self/maps) before the load, after it, and after a sweep and
a reference render; then it prints (and writes) a JSON report.

    blender -b --factory-startup --python tools/shafts_in_blender.py -- \\
        SOURCE_DIR LIBSHAFTS [REPORT.json]

Exits 1 if the library does not load, a render fails, or a library ends up
mapped from two different files (two copies of one library in a process).
"""
import json
import os
import re
import subprocess
import sys
import threading
import time


def mapped():
    """{file name: set of paths} of the shared objects mapped now."""
    libs = {}
    with open("/proc/self/maps") as f:
        for line in f:
            parts = line.split()
            if len(parts) >= 6 and re.search(r"\.so(\.|$)", parts[5]):
                libs.setdefault(os.path.basename(parts[5]), set()).add(parts[5])
    return libs


def stem(name):
    """libfoo.so.1.2 -> libfoo, to find two versions of one library."""
    return re.sub(r"(-[0-9_.]+)?\.so.*$", "", name)


def needed(lib):
    """The libraries the dynamic linker resolves for lib (ldd), by name."""
    out = subprocess.run(["ldd", lib], stdout=subprocess.PIPE, universal_newlines=True).stdout
    return sorted(line.split()[0] for line in out.splitlines() if "=>" in line)


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    source, lib = os.path.abspath(args[0]), os.path.abspath(args[1])
    report_path = args[2] if len(args) > 2 else None
    report = {"blender": None, "python": sys.version.split()[0], "library": lib}
    try:
        import bpy
        report["blender"] = bpy.app.version_string
    except ImportError:
        pass
    blender_only = mapped()
    import numpy  # noqa: F401 (shafts.py's own dependency, measured apart)
    before = mapped()
    report["mapped_by_numpy"] = len(set(before) - set(blender_only))
    sys.path.insert(0, os.path.join(source, "blender_addon", "shafts_blender"))
    start = time.perf_counter()
    import shafts
    shafts.load_library(lib)
    report["load_seconds"] = round(time.perf_counter() - start, 3)
    report["version"] = shafts.version()
    loaded = mapped()
    # ldd names libraries by soname, the maps by file: compare real paths.
    real_before = {os.path.realpath(p) for paths in before.values() for p in paths}
    deps = needed(lib)
    out = subprocess.run(["ldd", lib], stdout=subprocess.PIPE, universal_newlines=True).stdout
    resolved = {line.split()[0]: os.path.realpath(line.split()[2])
                for line in out.splitlines() if "=>" in line and len(line.split()) > 2}
    shared = sorted(d for d in deps if resolved.get(d) in real_before)
    report["needed"] = len(deps)
    report["needed_shared_with_blender"] = len(shared)
    report["needed_new"] = sorted(d for d in deps if d not in shared)
    report["mapped_by_load"] = sorted(set(loaded) - set(before))

    ok = True
    scene_file = os.path.join(source, "scenes", "teapot_spot.json")
    with open(scene_file) as f:
        data = json.load(f)
    data["camera"]["width"], data["camera"]["height"] = 160, 120
    with shafts.Scene.from_json(data, base_dir=os.path.dirname(scene_file)) as scene:
        # On Blender's main thread (where Blender's own GL context is
        # current when it has a window) and on a thread of its own, as the
        # add-on renders.
        for where in ("sweep_main_thread", "sweep_worker_thread"):
            result = {}

            def sweep():
                try:
                    start = time.perf_counter()
                    with shafts.SweepRenderer(scene) as r:
                        rgb, stats = r.draw()
                    result.update(seconds=round(time.perf_counter() - start, 3),
                                  backend=stats["backend"], renderer=stats["renderer"],
                                  mean=float(rgb.mean()))
                except shafts.ShaftsError as e:
                    result["error"] = str(e)

            if where == "sweep_main_thread":
                sweep()
            else:
                t = threading.Thread(target=sweep)
                t.start()
                t.join()
            report[where] = result
            ok &= result.get("mean", 0) > 0
        try:
            start = time.perf_counter()
            rgb, stats = shafts.render_reference(scene, spp=4)
            report["reference"] = {"seconds": round(time.perf_counter() - start, 3),
                                   "mean": float(rgb.mean())}
            ok &= bool(rgb.max() > 0)
        except shafts.ShaftsError as e:
            report["reference"] = {"error": str(e)}
            ok = False
    rendered = mapped()
    report["mapped_by_render"] = sorted(set(rendered) - set(loaded))
    # One library from two files (a bundled copy beside the system's).
    stems = {}
    for name, paths in rendered.items():
        for p in paths:
            stems.setdefault(stem(name), set()).add(os.path.realpath(p))
    report["two_copies"] = sorted(s for s, files in stems.items() if len(files) > 1)
    ok &= not report["two_copies"]
    report["ok"] = bool(ok)
    text = json.dumps(report, indent=2)
    print(text)
    if report_path:
        with open(report_path, "w") as f:
            f.write(text + "\n")
    sys.stdout.flush()
    os._exit(0 if ok else 1)


main()
