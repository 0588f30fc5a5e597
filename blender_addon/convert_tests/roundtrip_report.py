"""What a round trip costs, scene by scene (docs/blender.md, Mapping):

    blender -b --factory-startup --python roundtrip_report.py -- BUILD_DIR [SCENE.json...]

Each scene (default: scene_export/testdata/*.json) is imported with the
add-on's importer, exported again (JSON and PLY files), and both files are
rendered by lmm_tracer's reference mode (96x72, 16 samples, seed 1). Prints
the mean relative difference over the lit pixels (the original's value
above 1% of its largest), the ratio of the sums, and the number of notes
the import (scene_export's writer) and warnings the export gave."""
import glob
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import bpy
import harness as H
from shafts_blender.convert import export_scene, importer
from shafts_blender.convert.files import write_files


build = H.build_dir()
args = H.args()[1:]
root = os.path.dirname(os.path.dirname(H.HERE))
scenes = args or sorted(glob.glob(os.path.join(root, "scene_export", "testdata", "*.json")))
size = (96, 72)
print("%-26s %10s %8s %7s %9s" % ("scene", "mean_rel", "ratio", "notes", "warnings"))
for path in scenes:
    work = tempfile.mkdtemp(prefix="roundtrip_")
    src = H.scene_copy(path, work, size)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    notes = importer.import_scene(bpy.context, src, lib_path=os.path.join(build, "libshafts.so"))
    e = export_scene(bpy.context.evaluated_depsgraph_get())
    out = os.path.join(work, "back.json")
    write_files(e, out)
    rel, ratio = H.render_difference(build, src, out, work)
    print("%-26s %10.4f %8.4f %7d %9d" % (os.path.basename(path)[:-5], rel, ratio,
                                           len(notes), len(e.warnings)))
sys.stdout.flush()
