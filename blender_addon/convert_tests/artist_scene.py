"""Scenes built by script the way an artist builds them in Blender's UI,
shared by the convert tests."""
import math

import bpy


def reset():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    return bpy.context.scene


def add_object(scene, name, data, location=(0, 0, 0), rotation=(0, 0, 0), scale=(1, 1, 1)):
    obj = bpy.data.objects.new(name, data)
    scene.collection.objects.link(obj)
    obj.location, obj.rotation_euler, obj.scale = location, rotation, scale
    return obj


def cube_mesh(name, size=2.0):
    h = size / 2
    v = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    me = bpy.data.meshes.new(name)
    me.from_pydata(v, [], f)
    me.update()
    return me


def plane_mesh(name, size=2.0):
    h = size / 2
    me = bpy.data.meshes.new(name)
    me.from_pydata([(-h, -h, 0), (h, -h, 0), (h, h, 0), (-h, h, 0)], [], [(0, 1, 2, 3)])
    me.update()
    return me


def diffuse_material(name, colour):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    d = tree.nodes.new("ShaderNodeBsdfDiffuse")
    d.inputs["Color"].default_value = tuple(colour) + (1.0,)
    tree.links.new(d.outputs[0], tree.nodes["Material Output"].inputs["Surface"])
    return mat


def volume_material(name, kind, colour=(0.8, 0.8, 0.8), density=0.1, anisotropy=0.0,
                    absorption_colour=(0, 0, 0)):
    """A volume-only material: 'principled' (Principled Volume) or
    'scatter_absorption' (Volume Scatter + Volume Absorption)."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    tree = mat.node_tree
    tree.nodes.remove(tree.nodes["Principled BSDF"])
    out = tree.nodes["Material Output"]
    if kind == "principled":
        v = tree.nodes.new("ShaderNodeVolumePrincipled")
        v.inputs["Color"].default_value = tuple(colour) + (1.0,)
        v.inputs["Density"].default_value = density
        v.inputs["Anisotropy"].default_value = anisotropy
        v.inputs["Absorption Color"].default_value = tuple(absorption_colour) + (1.0,)
        tree.links.new(v.outputs[0], out.inputs["Volume"])
    else:
        s = tree.nodes.new("ShaderNodeVolumeScatter")
        s.inputs["Color"].default_value = tuple(colour) + (1.0,)
        s.inputs["Density"].default_value = density
        s.inputs["Anisotropy"].default_value = anisotropy
        a = tree.nodes.new("ShaderNodeVolumeAbsorption")
        a.inputs["Color"].default_value = tuple(absorption_colour) + (1.0,)
        a.inputs["Density"].default_value = density
        add = tree.nodes.new("ShaderNodeAddShader")
        tree.links.new(s.outputs[0], add.inputs[0])
        tree.links.new(a.outputs[0], add.inputs[1])
        tree.links.new(add.outputs[0], out.inputs["Volume"])
    return mat


def world_volume(scene, density, anisotropy=0.0):
    """A World with a black background and a Volume Scatter volume."""
    world = bpy.data.worlds.new("World")
    scene.world = world
    world.use_nodes = True
    tree = world.node_tree
    tree.nodes["Background"].inputs["Color"].default_value = (0, 0, 0, 1)
    scatter = tree.nodes.new("ShaderNodeVolumeScatter")
    scatter.inputs["Density"].default_value = density
    scatter.inputs["Anisotropy"].default_value = anisotropy
    tree.links.new(scatter.outputs[0], tree.nodes["World Output"].inputs["Volume"])
    return world


def camera(scene, location, rotation_deg, lens=50.0, sensor_fit="AUTO", size=(64, 48)):
    data = bpy.data.cameras.new("Camera")
    data.lens = lens
    data.sensor_fit = sensor_fit
    obj = add_object(scene, "Camera", data, location,
                     tuple(math.radians(a) for a in rotation_deg))
    scene.camera = obj
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    return obj


def light(scene, name, kind, watts, location, rotation_deg=(0, 0, 0), colour=(1, 1, 1),
          **settings):
    data = bpy.data.lights.new(name, kind)
    data.energy = watts
    data.color = colour
    for key, value in settings.items():
        setattr(data, key, value)
    return add_object(scene, name, data, location,
                      tuple(math.radians(a) for a in rotation_deg))


def spot_in_volume_box(volume_kind="principled"):
    """A spot and a caster in a volume box over a Diffuse BSDF floor."""
    scene = reset()
    camera(scene, (0, -8, 3), (75, 0, 0))
    light(scene, "Spot", "SPOT", 500.0, (0, 0, 4), spot_size=math.radians(50),
          spot_blend=0.3, shadow_soft_size=0.0)
    floor = add_object(scene, "Floor", plane_mesh("Floor", 10.0))
    floor.data.materials.append(diffuse_material("Floor", (0.5, 0.5, 0.5)))
    caster = add_object(scene, "Caster", cube_mesh("Caster", 1.0), (0, 0, 1.5))
    caster.data.materials.append(diffuse_material("Caster", (0.8, 0.2, 0.2)))
    box = add_object(scene, "Fog", cube_mesh("Fog", 2.0), (0, 0, 2.5), scale=(5, 5, 2.5))
    box.data.materials.append(volume_material("Fog", volume_kind, colour=(0.9, 0.8, 0.7),
                                              density=0.2, anisotropy=0.4,
                                              absorption_colour=(0.25, 0.25, 0.25)))
    return scene
