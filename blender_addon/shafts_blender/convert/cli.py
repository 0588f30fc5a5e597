"""The Blender side of tools/blend2shafts: run inside Blender on an opened
.blend file,

    blender -b FILE.blend --python-exit-code 1 --python cli.py -- FILE.blend OUT.json

registers the add-on's properties (properties.py) unless the add-on did,
exports the scene (export_scene, files.write_files) and prints the
approximations on stderr. Exit status: 0; 2 if Blender did not open FILE.blend
or OUT.json is not a writable .json path; 1 if writing fails (nothing is
left half-written)."""
import os
import sys


def main():
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    import bpy
    from shafts_blender import properties
    from shafts_blender.convert import files
    from shafts_blender.convert.scene import export_scene

    # The add-on's settings (a material's Shafts Medium above all) are read
    # through their property groups, which a Blender without the add-on
    # enabled has not registered: the .blend keeps them as plain ID
    # properties until these are.
    if not hasattr(bpy.types.Material, "shafts_medium"):
        for cls in properties.classes:
            bpy.utils.register_class(cls)
        properties.register()

    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 2:
        print("blend2shafts: expected FILE.blend OUT.json", file=sys.stderr)
        return 2
    blend, out = (os.path.abspath(a) for a in argv)
    if not bpy.data.filepath or os.path.abspath(bpy.data.filepath) != blend:
        print("blend2shafts: error: Blender could not open %s" % blend, file=sys.stderr)
        return 2
    export = export_scene(bpy.context.evaluated_depsgraph_get())
    for w in export.warnings:
        print("blend2shafts: warning: %s" % w, file=sys.stderr)
    try:
        written = files.write_files(export, out)
    except OSError as e:
        print("blend2shafts: error: cannot write %s: %s" % (out, e), file=sys.stderr)
        return 1
    print("blend2shafts: wrote %s (%d mesh file%s, %d approximation%s)"
          % (out, len(written) - 1, "" if len(written) == 2 else "s",
             len(export.warnings), "" if len(export.warnings) == 1 else "s"))
    return 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)
