"""The operators: File > Import > Shafts scene (.json) and File > Export >
Shafts scene (.json)."""
import os

import bpy
from bpy.props import StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import files, importer
from .scene import export_scene


def _report_warnings(op, warnings, verb):
    for w in warnings:
        op.report({"WARNING"}, w)
    if warnings:
        op.report({"WARNING"}, "%s with %d approximation%s (listed above)."
                  % (verb, len(warnings), "" if len(warnings) == 1 else "s"))


class SHAFTS_OT_import_scene(bpy.types.Operator, ImportHelper):
    """Import a Shafts scene (.json): the scene as scene_export --to blender
    builds it for Cycles"""
    bl_idname = "shafts.import_scene"
    bl_label = "Import Shafts scene"
    bl_options = {"REGISTER", "UNDO"}
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def execute(self, context):
        try:
            notes = importer.import_scene(context, self.filepath)
        except (importer.ImportFailed, OSError, ValueError) as e:
            self.report({"ERROR"}, "Cannot import %s: %s" % (self.filepath, e))
            return {"CANCELLED"}
        _report_warnings(self, notes, "Imported")
        return {"FINISHED"}


class SHAFTS_OT_export_scene(bpy.types.Operator, ExportHelper):
    """Export the scene as a Shafts scene (.json) with its meshes as PLY
    files beside it"""
    bl_idname = "shafts.export_scene"
    bl_label = "Export Shafts scene"
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={"HIDDEN"})

    def execute(self, context):
        try:
            export = export_scene(context.evaluated_depsgraph_get())
            written = files.write_files(export, self.filepath)
        except OSError as e:
            self.report({"ERROR"}, "Cannot write %s: %s" % (self.filepath, e))
            return {"CANCELLED"}
        _report_warnings(self, export.warnings, "Exported")
        self.report({"INFO"}, "Wrote %s and %d mesh file%s."
                    % (os.path.basename(self.filepath), len(written) - 1,
                       "" if len(written) == 2 else "s"))
        return {"FINISHED"}


def menu_import(self, context):
    self.layout.operator(SHAFTS_OT_import_scene.bl_idname, text="Shafts scene (.json)")


def menu_export(self, context):
    self.layout.operator(SHAFTS_OT_export_scene.bl_idname, text="Shafts scene (.json)")


classes = (SHAFTS_OT_import_scene, SHAFTS_OT_export_scene)
menu_funcs = ((bpy.types.TOPBAR_MT_file_import, menu_import),
              (bpy.types.TOPBAR_MT_file_export, menu_export))
