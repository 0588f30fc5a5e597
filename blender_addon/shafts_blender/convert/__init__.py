"""Blender <-> scene conversion (docs/blender.md, Mapping).

    from .convert import export_scene, export_patch
    export_scene(depsgraph, view=None, size=None) -> Export
    export_patch(depsgraph, previous, view=None, size=None) -> dict | None

`classes` (the operators) and `menu_funcs` ((menu, function) pairs for
File > Import and File > Export) are registered by the add-on's
__init__.py.
"""
from .scene import Export, export_patch, export_scene  # noqa: F401

classes = ()
menu_funcs = ()
