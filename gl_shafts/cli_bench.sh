#!/usr/bin/env bash
# The command line's speed: how long gl_shafts and lmm_tracer take as
# processes, start-up included (issue 13 part 4). Times, as a user would
# run them, `gl_shafts --help`, `lmm_tracer --help` and the teapot
# spotlight (scenes/teapot_spot.json at its own size) to a PNG and to an
# EXR, each after one warm-up run (so the "second run": files in the page
# cache, the program caches filled). Prints a Markdown table: the
# median wall time and CPU time (user + system) of the runs, the peak
# memory, and the shared libraries the program is linked to (ldd, before
# anything it loads later with dlopen); then where one PNG run's time goes
# (gl_shafts --stats); then the teapot's second run with gl_shafts' program
# cache on disk and Mesa's shader cache each on or off (fresh directories).
#
# With --baseline-rev REV (a commit, e.g. the one before the change) the
# same commands run, interleaved run by run, on a build of that commit too
# (made once under BUILD/cli_bench/REV: gl_shafts and lmm_tracer only), and
# the table gives both and their ratios, measured in one run on one load.
#
#   gl_shafts/cli_bench.sh [--build DIR] [--runs N] [--baseline-rev REV]
#                          [--baseline DIR]
#
# --baseline DIR takes an existing build directory instead of REV.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build runs=10 base_rev="" base=""
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --runs) runs=$2; shift 2 ;;
    --baseline-rev) base_rev=$2; shift 2 ;;
    --baseline) base=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    *) echo "cli_bench.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
for exe in gl_shafts/gl_shafts lmm_tracer/lmm_tracer; do
  [ -x "$build/$exe" ] || { echo "cli_bench.sh: build first: $build/$exe is missing" >&2; exit 2; }
done

if [ -n "$base_rev" ]; then
  rev=$(git -C "$root" rev-parse --short "$base_rev^{commit}")
  base=$build/cli_bench/$rev
  if [ ! -x "$base/build/gl_shafts/gl_shafts" ] || [ ! -x "$base/build/lmm_tracer/lmm_tracer" ]; then
    echo "cli_bench.sh: building $rev in $base (once)" >&2
    rm -rf "$base" && mkdir -p "$base/src"
    git -C "$root" archive "$rev" | tar -x -C "$base/src"
    cmake -S "$base/src" -B "$base/build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
    cmake --build "$base/build" -j2 --target gl_shafts lmm_tracer >/dev/null
  fi
  base=$base/build
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$root"
echo "machine: $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)," \
     "$(date -u +%Y-%m-%dT%H:%MZ), $runs runs a command"
# Both builds' caches of compiled programs (Mesa's, gl_shafts') start empty
# in the work directory; the warm-up runs fill them.
export MESA_SHADER_CACHE_DIR=$work/mesa SHAFTS_PROGRAM_CACHE=$work/programs
python3 - "$build" "$base" "$runs" "$work" <<'EOF'
import os, resource, statistics, subprocess, sys, time, json

build, base, runs, work = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
scene = "scenes/teapot_spot.json"
commands = [
    ("gl_shafts --help", "gl_shafts/gl_shafts", ["--help"]),
    ("lmm_tracer --help", "lmm_tracer/lmm_tracer", ["--help"]),
    ("gl_shafts teapot -o out.png", "gl_shafts/gl_shafts", [scene, "-o", "OUT.png", "-q"]),
    ("gl_shafts teapot -o out.exr", "gl_shafts/gl_shafts", [scene, "-o", "OUT.exr", "-q"]),
]
builds = [("after", build)] + ([("before", base)] if base else [])

def run_once(exe, args, tag):
    args = [a.replace("OUT", os.path.join(work, tag)) for a in args]
    t0 = time.perf_counter()
    p = subprocess.Popen([exe] + args, stdout=subprocess.DEVNULL)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    if status != 0:
        sys.exit("cli_bench.sh: %s %s failed" % (exe, " ".join(args)))
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0

def libs(exe):
    out = subprocess.run(["ldd", exe], capture_output=True, text=True).stdout
    return sum(1 for l in out.splitlines() if "=>" in l or l.strip().startswith("/"))

res = {}
for name, rel, args in commands:
    for tag, b in builds:
        run_once(os.path.join(b, rel), args, tag)  # warm-up: the "second run"
    samples = {tag: [] for tag, _ in builds}
    for i in range(runs):
        order = builds if i % 2 == 0 else builds[::-1]
        for tag, b in order:
            samples[tag].append(run_once(os.path.join(b, rel), args, tag))
    for tag, b in builds:
        s = samples[tag]
        res[name, tag] = (statistics.median(x[0] for x in s) * 1e3,
                          statistics.median(x[1] for x in s) * 1e3,
                          max(x[2] for x in s), libs(os.path.join(b, rel)))

print()
if base:
    print("| command | wall ms before | wall ms after | before/after | CPU ms before "
          "| CPU ms after | before/after | MiB before | MiB after | libraries before | after |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, _, _ in commands:
        w1, c1, m1, l1 = res[name, "before"]
        w2, c2, m2, l2 = res[name, "after"]
        print("| `%s` | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.0f | %.0f | %d | %d |"
              % (name, w1, w2, w1 / w2, c1, c2, c1 / c2, m1, m2, l1, l2))
else:
    print("| command | wall ms | CPU ms | MiB | libraries |")
    print("|---|---:|---:|---:|---:|")
    for name, _, _ in commands:
        w, c, m, l = res[name, "after"]
        print("| `%s` | %.1f | %.1f | %.0f | %d |" % (name, w, c, m, l))

# Where one PNG run's time goes: the renderer's own clocks (--stats) against
# the process's wall time; the rest is start-up, loading the scene and its
# mesh, writing the image and exit.
print()
print("| build | process wall ms | context, upload, programs ms | programs compiled "
      "| frame ms | the rest ms |")
print("|---|---:|---:|---:|---:|---:|")
for tag, b in builds:
    stats = os.path.join(work, tag + ".json")
    walls, sets, frames, comp = [], [], [], []
    for i in range(max(3, runs // 2)):
        w, _, _ = run_once(os.path.join(b, "gl_shafts/gl_shafts"),
                           [scene, "-o", "OUT.png", "-q", "--stats", stats], tag)
        st = json.load(open(stats))
        walls.append(w * 1e3)
        sets.append(st["setup_seconds"] * 1e3)
        frames.append(st["seconds"] * 1e3)
        comp.append(st.get("programs_compiled", 0))
    w, s, f = (statistics.median(v) for v in (walls, sets, frames))
    print("| %s | %.0f | %.0f | %d | %.0f | %.0f |" % (tag, w, s, max(comp), f, w - s - f))
# The two caches of compiled programs on the second run, gl_shafts' own on
# disk (ARB_get_program_binary, gs_program_cache.h) and Mesa's shader cache
# (which also keeps llvmpipe's machine code), each on or off, each in a
# directory of its own filled by a warm-up run; configurations interleaved.
print()
print("| program caches (teapot -o out.png, second run) | wall ms | CPU ms "
      "| frame ms (programs and drawing) | programs on disk |")
print("|---|---:|---:|---:|---:|")
exe = os.path.join(build, "gl_shafts/gl_shafts")
configs = [("both (the default)", {}),
           ("Mesa's only", {"SHAFTS_PROGRAM_CACHE": "off"}),
           ("gl_shafts' only", {"MESA_SHADER_CACHE_DISABLE": "true"}),
           ("neither", {"SHAFTS_PROGRAM_CACHE": "off", "MESA_SHADER_CACHE_DISABLE": "true"})]
envs = []
for i, (name, extra) in enumerate(configs):
    e = dict(os.environ)
    e["MESA_SHADER_CACHE_DIR"] = os.path.join(work, "mesa%d" % i)
    e["SHAFTS_PROGRAM_CACHE"] = os.path.join(work, "programs%d" % i)
    e.update(extra)
    envs.append(e)

def run_env(e, tag):
    stats = os.path.join(work, tag + ".json")
    t0 = time.perf_counter()
    p = subprocess.Popen([exe, scene, "-o", os.path.join(work, tag + ".png"), "-q",
                          "--stats", stats], env=e)
    _, status, ru = os.wait4(p.pid, 0)
    if status != 0:
        sys.exit("cli_bench.sh: gl_shafts failed")
    return ((time.perf_counter() - t0) * 1e3, (ru.ru_utime + ru.ru_stime) * 1e3,
            json.load(open(stats))["seconds"] * 1e3)

for i, e in enumerate(envs):
    run_env(e, "cfg%d" % i)
samples = [[] for _ in configs]
for r in range(runs):
    order = range(len(configs)) if r % 2 == 0 else reversed(range(len(configs)))
    for i in order:
        samples[i].append(run_env(envs[i], "cfg%d" % i))
for i, (name, _) in enumerate(configs):
    d = envs[i]["SHAFTS_PROGRAM_CACHE"]
    files = len(os.listdir(d)) if os.path.isdir(d) else 0
    w, c, f = (statistics.median(x[k] for x in samples[i]) for k in range(3))
    print("| %s | %.0f | %.0f | %.0f | %d |" % (name, w, c, f, files))
EOF
