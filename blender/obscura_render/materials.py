"""Blender materials as UsdPreviewSurface values (docs/schemas.md#material).

A material whose surface output is a Principled BSDF maps its inputs onto the UsdPreviewSurface
inputs Obscura has, as Blender's USD exporter maps them (usd_writer_material.cc): Base Color ->
diffuseColor, Metallic, Roughness, Emission x Emission Strength -> emissiveColor, Alpha ->
opacity, IOR, Clearcoat; an Image Texture node on one of these (or behind a Normal Map node on
Normal) becomes that input's texture, a Mapping node on its Vector its coordinate transform. Anything else falls back to the material's viewport display
colour (Material.diffuse_color, metallic, roughness) with one warning naming the material.
"""

from __future__ import annotations

import math

import bpy

# Principled BSDF socket -> (UsdPreviewSurface input, texture channel read for it).
_SCALAR_INPUTS = {"Metallic": "metallic", "Roughness": "roughness", "Alpha": "opacity"}
_TEXTURED = {"Base Color": ("diffuseColor", "rgb"), "Metallic": ("metallic", "r"), "Roughness": ("roughness", "r"),
             "Alpha": ("opacity", "r"), "Emission": ("emissiveColor", "rgb")}


class Unsupported(Exception):
    """The node tree uses something this mapping does not know: the reason, for the warning."""


def linked_node(socket):
    if not socket.is_linked:
        return None
    link = socket.links[0]
    if not link.is_valid:
        raise Unsupported(f"an invalid link into {socket.name}")
    return link.from_node


def image_file(node) -> str:
    image = node.image
    if image is None:
        raise Unsupported(f"the Image Texture node {node.name!r} has no image")
    if image.packed_file is not None or image.source != "FILE":
        raise Unsupported(f"the image {image.name!r} is not a file on disk (packed or generated)")
    return bpy.path.abspath(image.filepath_raw, library=image.library)


def _coordinate_transform(node, prefix: str) -> dict:
    """A Mapping node (type Point) on the Image Texture's Vector, as Blender's USD exporter writes it
    into a UsdTransform2d: location + rotate(Z rotation) (scale uv), the rows of
    obscura:<input>:transformS and transformT. Other nodes there (UV Map, Texture Coordinate) read
    the mesh's UVs unchanged."""
    mapping = linked_node(node.inputs["Vector"])
    if mapping is None or mapping.bl_idname != "ShaderNodeMapping":
        return {}
    sockets = ("Location", "Rotation", "Scale")
    if mapping.vector_type != "POINT" or any(mapping.inputs[name].is_linked for name in sockets):
        raise Unsupported(f"the Mapping node {mapping.name!r} (only a Point mapping with constant inputs maps)")
    location, rotation, scale = (mapping.inputs[name].default_value for name in sockets)
    if rotation[0] != 0.0 or rotation[1] != 0.0:
        raise Unsupported(f"the Mapping node {mapping.name!r} rotates about X or Y")
    c, s = math.cos(rotation[2]), math.sin(rotation[2])
    return {prefix + "transformS": (c * scale[0], -s * scale[1], location[0]),
            prefix + "transformT": (s * scale[0], c * scale[1], location[1])}


def _texture(node, usd_input: str, channel: str) -> dict:
    if node.bl_idname != "ShaderNodeTexImage":
        raise Unsupported(f"a {node.bl_label} node on {usd_input}")
    raw = node.image is not None and node.image.colorspace_settings.is_data
    wrap = {"REPEAT": "repeat", "EXTEND": "clamp", "MIRROR": "mirror", "CLIP": "black"}.get(node.extension, "repeat")
    prefix = f"obscura:{usd_input}:"
    return {prefix + "file": image_file(node), prefix + "channel": channel, prefix + "wrapS": wrap,
            prefix + "wrapT": wrap, prefix + "sourceColorSpace": "raw" if raw else "sRGB",
            **_coordinate_transform(node, prefix)}


def principled_values(bsdf) -> dict:
    """UsdPreviewSurface values of a Principled BSDF node; raises Unsupported."""
    inputs = bsdf.inputs
    values = {"inputs:useSpecularWorkflow": 0}
    for socket_name, (usd_input, channel) in _TEXTURED.items():
        node = linked_node(inputs[socket_name])
        if node is not None:
            values.update(_texture(node, usd_input, channel))
    base = inputs["Base Color"].default_value
    values["inputs:diffuseColor"] = (base[0], base[1], base[2])
    for socket_name, usd_input in _SCALAR_INPUTS.items():
        values[f"inputs:{usd_input}"] = float(inputs[socket_name].default_value)
    strength = float(inputs["Emission Strength"].default_value)
    emission = inputs["Emission"].default_value
    values["inputs:emissiveColor"] = tuple(float(c) * strength for c in emission[:3])
    if "obscura:emissiveColor:file" in values:
        values["obscura:emissiveColor:scale"] = (strength, strength, strength, 1.0)
    values["inputs:ior"] = float(inputs["IOR"].default_value)
    values["inputs:clearcoat"] = float(inputs["Clearcoat"].default_value)
    values["inputs:clearcoatRoughness"] = float(inputs["Clearcoat Roughness"].default_value)
    # Obscura's anisotropic lobe; the rotation is a fraction of a turn, as in MaterialX. (Cycles
    # stretches its lobe by its own aspect of the same value, so highlights differ in length.)
    values["inputs:obscura:anisotropy"] = float(inputs["Anisotropic"].default_value)
    values["inputs:obscura:anisotropyRotation"] = 360.0 * float(inputs["Anisotropic Rotation"].default_value)
    normal = linked_node(inputs["Normal"])
    if normal is not None:
        if normal.bl_idname != "ShaderNodeNormalMap" or normal.space != "TANGENT":
            raise Unsupported(f"a {normal.bl_label} node on Normal (only a tangent-space Normal Map node maps)")
        image = linked_node(normal.inputs["Color"])
        if image is not None:
            values.update(_texture(image, "normal", "rgb"))
            # Tangent-space texels in [0, 1] to [-1, 1] (UsdPreviewSurface's normal input), the
            # node's Strength scaling the tangent-plane part.
            s = float(normal.inputs["Strength"].default_value)
            values["obscura:normal:scale"] = (2.0 * s, 2.0 * s, 2.0, 1.0)
            values["obscura:normal:bias"] = (-s, -s, -1.0, 0.0)
            values["obscura:normal:sourceColorSpace"] = "raw"
    return values


def _surface_bsdf(material):
    output = material.node_tree.get_output_node("ALL") if material.node_tree else None
    if output is None:
        raise Unsupported("no Material Output node")
    node = linked_node(output.inputs["Surface"])
    if node is None:
        raise Unsupported("nothing connected to the Material Output's Surface")
    if node.bl_idname != "ShaderNodeBsdfPrincipled":
        raise Unsupported(f"a {node.bl_label} node on the Surface output")
    return node


def viewport_display_values(material) -> dict:
    """The material's viewport display settings (Material > Viewport Display)."""
    c = material.diffuse_color
    return {"inputs:diffuseColor": (c[0], c[1], c[2]), "inputs:opacity": float(c[3]),
            "inputs:metallic": float(material.metallic), "inputs:roughness": float(material.roughness)}


def material_values(material) -> tuple[dict, str | None]:
    """(values, warning): the mapped Principled BSDF, or the viewport display colour and why."""
    if not material.use_nodes:
        return viewport_display_values(material), None
    try:
        return principled_values(_surface_bsdf(material)), None
    except Unsupported as e:
        return (viewport_display_values(material),
                f"material {material.name!r}: {e}; rendered with its viewport display colour")
