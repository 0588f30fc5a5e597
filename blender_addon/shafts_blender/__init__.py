"""Shafts: the light shafts toolkit's renderers as Blender render engines.

SHAFTS_SWEEP renders with gl_shafts' plane sweep (a live viewport too);
SHAFTS_TRACER with lmm_tracer (the converged reference by default, Whitted
or light meshes). The scene is converted in memory (convert/) and rendered
in-process through libshafts.so, which ships beside shafts.py in this
package. docs/blender.md of the repository tells the rest.
"""
bl_info = {
    "name": "Shafts",
    "author": "shafts developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > Render Engine",
    "description": "Light shafts in participating media: gl_shafts' plane sweep "
                   "and lmm_tracer as render engines",
    "doc_url": "",
    "category": "Render",
}

import bpy

from . import engine, panels, properties


def _convert():
    """The converter package when it is present (it brings its own operators
    and menu entries)."""
    try:
        from . import convert
    except ImportError:
        return None
    return convert


def _classes():
    convert = _convert()
    extra = tuple(getattr(convert, "classes", ())) if convert else ()
    return properties.classes + engine.classes + panels.classes + extra


def _menus():
    convert = _convert()
    return tuple(getattr(convert, "menu_funcs", ())) if convert else ()


def register():
    for cls in _classes():
        bpy.utils.register_class(cls)
    properties.register()
    panels.register()
    for menu, func in _menus():
        menu.append(func)


def unregister():
    for menu, func in reversed(_menus()):
        menu.remove(func)
    panels.unregister()
    properties.unregister()
    for cls in reversed(_classes()):
        bpy.utils.unregister_class(cls)
