"""Hard cases of bad input and files (issue 11, kinds 5 to 8): each runs a
renderer's command line on an input a user may hand it and checks that it
is refused as it must be (the exit status, a message saying why, and no
file written or changed), or, for kind 8, that the fuzzing harnesses' seed
corpus runs clean. They are rows of the hard-case report beside the
rendering cases (validation/hard/runner.py)."""

import json
import os
import subprocess
from dataclasses import dataclass
from pathlib import Path

SCENE = {"format": "shafts-scene", "version": 1,
         "camera": {"position": [0, 1, 5], "look_at": [0, 0.5, 0], "fov_y_deg": 45,
                    "width": 8, "height": 6},
         "medium": {"sigma_s": [0.1, 0.1, 0.1],
                    "bounds": {"min": [-3, 0, -3], "max": [3, 3, 3]}},
         "lights": [{"type": "point", "position": [0, 2, 0], "intensity": [5, 5, 5]}],
         "materials": {"m": {"diffuse": [0.5, 0.5, 0.5]}},
         "shapes": [{"type": "quad", "material": "m", "corner": [-3, 0, 3],
                     "u": [6, 0, 0], "v": [0, 0, -6]}]}


def _scene(d, **changes):
    s = json.loads(json.dumps(SCENE))
    s.update(changes)
    path = Path(d) / "scene" / "s.json"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(s))
    return path


def _gltf_scene(d, uri):
    """The scene with a glTF mesh, mesh.gltf, whose buffer is named `uri`
    (a triangle of three float vertices, 36 bytes)."""
    scene = _scene(d, shapes=SCENE["shapes"] + [{"type": "mesh", "material": "m",
                                                  "file": "mesh.gltf"}])
    gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
            "buffers": [{"byteLength": 36, "uri": uri}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                           "min": [0, 0, 0], "max": [0, 0, 0]}]}
    (scene.parent / "mesh.gltf").write_text(json.dumps(gltf))
    return scene


def _escape(d):
    """A glTF whose buffer is named '../secret.bin' (shared/cases/gltf_escape)."""
    (Path(d) / "secret.bin").write_bytes(bytes(48))
    scene = _gltf_scene(d, "../secret.bin")
    return [str(scene), "-o", str(scene.parent / "out.exr")]


def _absolute(d):
    obj = Path(d) / "tet.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    scene = _scene(d, shapes=SCENE["shapes"] + [{"type": "mesh", "material": "m",
                                                  "file": str(obj.resolve())}])
    return [str(scene), "-o", str(scene.parent / "out.exr")]


def _output_is_buffer(d):
    """--stats naming the .bin buffer of the scene's glTF mesh (-o must end
    in .exr or .png)."""
    scene = _gltf_scene(d, "mesh.bin")
    (scene.parent / "mesh.bin").write_bytes(bytes(36))
    return [str(scene), "-o", str(scene.parent / "out.exr"), "--stats",
            str(scene.parent / "mesh.bin")]


def _stats_is_scene(d):
    scene = _scene(d)
    return [str(scene), "-o", str(scene.parent / "out.exr"), "--stats",
            str(scene.parent / "." / "s.json")]


def _dev_zero(d):
    (Path(d) / "scene").mkdir(parents=True, exist_ok=True)
    return ["/dev/zero", "-o", str(Path(d) / "scene" / "out.exr")]


def _many_lights(d):
    scene = _scene(d, lights=[dict(SCENE["lights"][0], intensity=[0.01] * 3)] * 257)
    return [str(scene), "-o", str(scene.parent / "out.exr")]


KNOWN = Path(__file__).resolve().parents[2] / "fuzz" / "known"


def _ply(d, data):
    scene = _scene(d, shapes=SCENE["shapes"] + [{"type": "mesh", "material": "m",
                                                  "file": "m.ply"}])
    (scene.parent / "m.ply").write_bytes(data)
    return [str(scene), "-o", str(scene.parent / "out.exr")]


def _ply_hang(d):
    """fuzz/known/ply_hang without its first byte (the harness's format
    pick): a PLY header with no end_header line."""
    return _ply(d, (KNOWN / "ply_hang").read_bytes()[1:])


def _ply_count(d):
    return _ply(d, b"ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\n"
                b"property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n")


@dataclass
class InputCase:
    name: str
    kind: int
    description: str
    args: object           # (scratch dir) -> command-line arguments after the tool
    message: str           # what the error must say
    only: tuple = ()       # renderers it applies to (empty: both)


INPUT_CASES = [
    InputCase("escape_gltf", 5, "a glTF whose buffer URI is ../secret.bin, outside the "
              "scene's tree: refused, the file never opened", _escape, "outside the scene's"),
    InputCase("absolute_name", 5, "a scene file naming its mesh by an absolute path: refused",
              _absolute, "is absolute"),
    InputCase("stats_is_scene", 6, "--stats naming the scene itself (spelled ./s.json): "
              "refused before any work, the scene unchanged", _stats_is_scene,
              "must not overwrite an input"),
    InputCase("output_is_buffer", 6, "--stats naming the .bin buffer of the scene's glTF mesh: "
              "refused before any work, the buffer unchanged", _output_is_buffer,
              "must not overwrite an input"),
    InputCase("scene_dev_zero", 7, "/dev/zero as the scene: refused at once, not read "
              "until memory runs out", _dev_zero, "not a regular file"),
    InputCase("too_many_lights", 7, "257 point lights: more than gl_shafts' stated limit, "
              "refused with the count and the limit", _many_lights,
              "gl_shafts renders at most 256", only=("gl_shafts",)),
    InputCase("ply_hang", 8, "a PLY mesh whose header has no end_header line (fuzz/known/"
              "ply_hang, on which assimp's reader looped forever): refused at once, located",
              _ply_hang, "line 7: unknown header keyword 'e'"),
    InputCase("ply_count", 8, "a PLY mesh declaring 2e9 vertices in 200 bytes (assimp: 2 GB "
              "in 10 s and on): refused at once with the count", _ply_count,
              "declares 2000000000 instances"),
]


# The renderers whose command-line tools the input cases run: the
# project's own. The peers (POV-Ray, Cycles, EEVEE, the add-on's engines)
# read what scene_export writes, never the scene file these cases spoil.
CLI_TOOLS = ("lmm_tracer", "gl_shafts")


def _files(d):
    return sorted(str(p.relative_to(d)) + ":" + str(p.stat().st_size) + ":" +
                  str(p.stat().st_mtime_ns) for p in Path(d).rglob("*") if p.is_file())


def cli_tools(ctx, adapters):
    """{renderer: path of its command-line tool} for the adapters among
    CLI_TOOLS (a full run's peers have no tool of that name in the build)."""
    return {a.name: ctx.tool("%s/%s" % (a.name, a.name)) for a in adapters
            if a.name in CLI_TOOLS}


def run_inputs(ctx, adapters, scratch):
    """The input cases' entries for the hard-case results, one rendering row
    per renderer, with the check "input" (and, for kind 8, the seed corpus
    replays)."""
    entries = []
    tools = cli_tools(ctx, adapters)
    for case in INPUT_CASES:
        entry = {"name": case.name, "description": "issue 11, kind %d: %s" % (
            case.kind, case.description), "width": 0, "height": 0, "masked_pixels": 0,
            "reference": {}, "renderings": []}
        for name, tool in tools.items():
            if case.only and name not in case.only:
                continue
            d = Path(scratch) / ("input-%s-%s" % (case.name, name))
            d.mkdir(parents=True, exist_ok=True)
            args = case.args(d)
            before = _files(d)
            try:
                p = subprocess.run([str(tool)] + args + ["-q"], capture_output=True, text=True,
                                   timeout=60)
                status, err = p.returncode, p.stderr.strip()
            except subprocess.TimeoutExpired:
                status, err = None, "did not finish in 60 s"
            ok = status == 2 and case.message in err and _files(d) == before
            entries_note = "exit %s, %s: %s" % (
                status, "nothing written" if _files(d) == before else "FILES CHANGED", err[:300])
            entry["renderings"].append({
                "renderer": name, "label": "refuses", "kind": "input", "status": "ok",
                "checks": [{"name": "input", "ok": ok, "note": entries_note}], "ok": ok})
        entries.append(entry)
    # Kind 8: the fuzzing harnesses' seeds run clean (sanitized in
    # make test-asan; make fuzz and CI fuzz from them).
    entry = {"name": "fuzz_seeds", "description": "issue 11, kind 8: the scene parser's and "
             "the mesh loader's fuzzing harnesses on their committed seeds (fuzz/, "
             "docs/fuzzing.md)", "width": 0, "height": 0, "masked_pixels": 0,
             "reference": {}, "renderings": []}
    src = Path(__file__).resolve().parents[2] / "fuzz" / "corpus"
    for h in ("scene", "mesh"):
        tool = Path(ctx.build) / "fuzz" / ("%s_replay" % h)
        if not tool.exists() or not tools:
            continue
        p = subprocess.run([str(tool), str(src / h)], capture_output=True, text=True, timeout=300)
        ok = p.returncode == 0
        entry["renderings"].append({
            "renderer": next(iter(tools)), "label": "%s seeds" % h, "kind": "input",
            "status": "ok", "ok": ok,
            "checks": [{"name": "input", "ok": ok,
                        "note": "exit %d: %s" % (p.returncode, (p.stdout + p.stderr).strip()[-300:])}]})
    if entry["renderings"]:
        entries.append(entry)
    return entries
