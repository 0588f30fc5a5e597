"""Reading shader node trees: following links and taking input values.

Shared by the material, medium and world readers. A value that a link
drives (a texture, a math chain) has no constant in the scene format; it is
replaced by the mean colour of an Image Texture's image, or else by the
socket's own unlinked value, with a warning naming the material and node.
"""
import numpy as np


def source(socket):
    """The (node, output socket) feeding an input socket through reroutes,
    or (None, None) if unlinked."""
    seen = 0
    while socket.is_linked and seen < 64:
        link = socket.links[0]
        if not link.is_valid or getattr(link, "is_muted", False):
            return None, None
        node = link.from_node
        if node.bl_idname == "NodeReroute":
            socket = node.inputs[0]
            seen += 1
            continue
        return node, link.from_socket
    return None, None


def find_input(node, *names):
    """The first of the named inputs the node has (names change between
    Blender versions), or None."""
    for name in names:
        s = node.inputs.get(name)
        if s is not None:
            return s
    return None


def _image_mean(image):
    n = image.size[0] * image.size[1] * image.channels
    if n == 0:
        return None
    px = np.empty(n, dtype=np.float32)
    image.pixels.foreach_get(px)
    px = px.reshape(-1, image.channels)
    if image.channels >= 3:
        return [float(x) for x in px[:, :3].mean(axis=0)]
    return [float(px[:, 0].mean())] * 3


def colour(node, names, what, warnings):
    """An RGB input as a list of three floats >= 0 (a linked input: see the
    module's comment)."""
    s = find_input(node, *names) if isinstance(names, tuple) else node.inputs.get(names)
    if s is None:
        return [0.0, 0.0, 0.0]
    src, _ = source(s)
    if src is not None:
        if src.bl_idname == "ShaderNodeTexImage" and src.image is not None:
            mean = _image_mean(src.image)
            if mean is not None:
                warnings.add("%s has the image '%s' on the %s of '%s'; the scene takes "
                             "its mean colour (%.3g, %.3g, %.3g)."
                             % (what, src.image.name, s.name, node.name, *mean))
                return [max(0.0, x) for x in mean]
        warnings.add("%s drives the %s of '%s' by '%s'; the scene takes the input's own "
                     "value instead." % (what, s.name, node.name, src.name))
    v = s.default_value
    try:
        vals = [float(x) for x in v[:3]]
    except TypeError:
        vals = [float(v)] * 3
    return [max(0.0, x) for x in vals]


def scalar(node, names, what, warnings, default=0.0):
    s = find_input(node, *names) if isinstance(names, tuple) else node.inputs.get(names)
    if s is None:
        return default
    src, _ = source(s)
    if src is not None:
        warnings.add("%s drives the %s of '%s' by '%s'; the scene takes the input's own "
                     "value instead." % (what, s.name, node.name, src.name))
    return float(s.default_value)


def is_light_path_gate(node, socket):
    """Whether a Mix Shader's factor is the 'seen by traced rays' gate
    scene_export's Blender writer builds (max of Light Path's Is Camera, Is
    Glossy and Is Transmission Ray): 1 for those rays, 0 for rays that
    gather light."""
    wanted = {"Is Camera Ray", "Is Glossy Ray", "Is Transmission Ray"}
    found = set()

    def visit(n, s, depth):
        if n is None or depth > 8:
            return False
        if n.bl_idname == "ShaderNodeLightPath":
            found.add(s.name)
            return s.name in wanted
        if n.bl_idname == "ShaderNodeMath" and n.operation == "MAXIMUM":
            return all(visit(*source(n.inputs[k]), depth + 1) for k in (0, 1))
        return False

    return visit(node, socket, 0) and found == wanted
