#!/usr/bin/env python3
"""Writes depth_of_field.usda: chequered cards at three depths and small glowing spheres, seen
through an 85 mm lens at f/2 focused on the middle card (seed 000 "Depth of field"): the near card
and the far wall blur, the glowing spheres make bokeh. Run from this folder; the output is
committed. Units are centimetres (metersPerUnit 0.01), so focalLength and apertures read as mm."""
import math


def fmt(values):
    return "[" + ", ".join("(%g, %g, %g)" % v for v in values) + "]"


def ints(values):
    return "[" + ", ".join(str(v) for v in values) + "]"


def card(width, height, cells_x, cells_y):
    """A chequered card in the XY plane facing +Z: one quad per cell, a colour per face."""
    points, counts, indices, colours = [], [], [], []
    for j in range(cells_y + 1):
        for i in range(cells_x + 1):
            points.append((width * (i / cells_x - 0.5), height * (j / cells_y - 0.5), 0.0))
    for j in range(cells_y):
        for i in range(cells_x):
            a = j * (cells_x + 1) + i
            counts.append(4)
            indices += [a, a + 1, a + cells_x + 2, a + cells_x + 1]
            colours.append((0.8, 0.8, 0.75) if (i + j) % 2 == 0 else (0.08, 0.1, 0.16))
    return points, counts, indices, colours


def sphere(radius, rings=12, segments=24):
    points, counts, indices = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            points.append((radius * math.sin(theta) * math.cos(phi), radius * math.cos(theta),
                           -radius * math.sin(theta) * math.sin(phi)))
    for r in range(rings):
        for s in range(segments):
            a, b = r * segments + s, r * segments + (s + 1) % segments
            counts.append(4)
            indices += [a, a + segments, b + segments, b]
    return points, counts, indices


def card_prim(name, translate, width, height, cells_x, cells_y):
    p, c, i, col = card(width, height, cells_x, cells_y)
    return f'''
    def Mesh "{name}"
    {{
        double3 xformOp:translate = {translate}
        uniform token[] xformOpOrder = ["xformOp:translate"]
        int[] faceVertexCounts = {ints(c)}
        int[] faceVertexIndices = {ints(i)}
        point3f[] points = {fmt(p)}
        color3f[] primvars:displayColor = {fmt(col)} (
            interpolation = "uniform"
        )
        uniform token subdivisionScheme = "none"
    }}
'''


def glow_prim(name, translate, colour, radius=2.0):
    p, c, i = sphere(radius)
    return f'''
    def Mesh "{name}" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {{
        double3 xformOp:translate = {translate}
        uniform token[] xformOpOrder = ["xformOp:translate"]
        int[] faceVertexCounts = {ints(c)}
        int[] faceVertexIndices = {ints(i)}
        point3f[] points = {fmt(p)}
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/{colour}>
    }}
'''


def glow_material(name, emissive):
    return f'''
        def Material "{name}"
        {{
            token outputs:surface.connect = </World/Looks/{name}/Surface.outputs:surface>
            def Shader "Surface"
            {{
                uniform token info:id = "UsdPreviewSurface"
                color3f inputs:diffuseColor = (0, 0, 0)
                color3f inputs:emissiveColor = {emissive}
                token outputs:surface
            }}
        }}'''


glows = "".join(glow_prim(f"FarGlow{k}", (-150 + 75 * k, 70 + 30 * (k % 2), -600), "Warm" if k % 2 else "Cool")
                for k in range(5))
text = f'''#usda 1.0
(
    doc = "Depth of field: chequered cards at 1.5 m, 3 m and 9 m and glowing spheres, through an 85 mm f/2 lens focused at 3 m, 6 aperture blades."
    defaultPrim = "World"
    metersPerUnit = 0.01
    upAxis = "Y"
    startTimeCode = 1
    endTimeCode = 1
)

def Xform "World"
{{
    def Scope "Looks"
    {{{glow_material("Warm", (40, 22, 8))}{glow_material("Cool", (8, 20, 40))}
    }}
{card_prim("FarWall", (0, 0, -600), 600, 400, 30, 20)}{card_prim("FocusCard", (20, -5, 0), 40, 60, 8, 12)}{card_prim("NearCard", (-18, -5, 150), 14, 20, 4, 6)}{glows}{glow_prim("NearGlow", (12, 14, 150), "Warm", 0.4)}
    def DistantLight "Sun"
    {{
        float inputs:intensity = 2
        bool inputs:normalize = 1
        float3 xformOp:rotateXYZ = (-30, 20, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }}

    def DomeLight "Sky"
    {{
        float inputs:intensity = 0.3
    }}

    def Camera "Camera"
    {{
        float focalLength = 85
        float horizontalAperture = 36
        float verticalAperture = 24
        float fStop = 2
        float focusDistance = 300
        uniform int obscura:apertureBlades = 6
        float obscura:apertureRotation = 15
        float2 clippingRange = (10, 10000)
        double3 xformOp:translate = (0, 0, 300)
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}
}}
'''
with open("depth_of_field.usda", "w") as f:
    f.write(text)
