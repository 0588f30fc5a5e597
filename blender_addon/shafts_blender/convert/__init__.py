"""Blender <-> scene conversion (docs/blender.md, Mapping).

    from .convert import export_scene, export_patch
    export_scene(depsgraph, view=None, size=None) -> Export
    export_patch(depsgraph, previous, view=None, size=None) -> dict | None

`classes` (the import and export operators) and `menu_funcs` ((menu,
function) pairs for File > Import and File > Export) are registered by the
add-on's __init__.py.
"""
from .ops import classes, menu_funcs  # noqa: F401
from .scene import Export, export_patch, export_scene  # noqa: F401
