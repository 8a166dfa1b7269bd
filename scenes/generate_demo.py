#!/usr/bin/env python3
"""Writes demo.usda: the bundled demo scene (a ground, three objects with different materials,
a sun and a sphere light). Run from this folder; the output is committed."""
import math

from usda_pieces import world_header


def sphere(radius, rings=24, segments=48):
    points, normals, counts, indices = [], [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            normals.append(n)
            points.append(tuple(radius * c for c in n))
    for r in range(rings):
        for s in range(segments):
            a = r * segments + s
            b = r * segments + (s + 1) % segments
            counts.append(4)
            # Counter-clockwise seen from outside (USD rightHanded).
            indices += [a, a + segments, b + segments, b]
    return points, normals, counts, indices


def box(size):
    h = size / 2
    faces = [((1, 0, 0), (0, 1, 0)), ((-1, 0, 0), (0, 1, 0)), ((0, 1, 0), (0, 0, -1)),
             ((0, -1, 0), (0, 0, 1)), ((0, 0, 1), (0, 1, 0)), ((0, 0, -1), (0, 1, 0))]
    points, counts, indices = [], [], []
    for n, up in faces:
        right = (up[1] * n[2] - up[2] * n[1], up[2] * n[0] - up[0] * n[2], up[0] * n[1] - up[1] * n[0])
        base = len(points)
        for u, v in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            points.append(tuple(h * (n[i] + u * right[i] + v * up[i]) for i in range(3)))
        counts.append(4)
        indices += [base, base + 1, base + 2, base + 3]
    return points, counts, indices


def fmt(values):
    return "[" + ", ".join("(%g, %g, %g)" % v for v in values) + "]"


def ints(values):
    return "[" + ", ".join(str(v) for v in values) + "]"


def prototypes_scope(ball, crate, ball_look, crate_look):
    """The Prototypes scope of a PointInstancer holding a ball and a crate mesh (sphere() and box()
    results), each bound to a material under /World/Looks."""
    (sp, sn, sc, si), (bp, bc, bi) = ball, crate
    return f'''        def Scope "Prototypes"
        {{
            def Mesh "Ball"
            {{
                int[] faceVertexCounts = {ints(sc)}
                int[] faceVertexIndices = {ints(si)}
                point3f[] points = {fmt(sp)}
                normal3f[] normals = {fmt(sn)} (
                    interpolation = "vertex"
                )
                uniform token subdivisionScheme = "none"
                rel material:binding = </World/Looks/{ball_look}>
            }}

            def Mesh "Crate"
            {{
                int[] faceVertexCounts = {ints(bc)}
                int[] faceVertexIndices = {ints(bi)}
                point3f[] points = {fmt(bp)}
                uniform token subdivisionScheme = "none"
                rel material:binding = </World/Looks/{crate_look}>
            }}
        }}'''


def material(name, diffuse, roughness, metallic=0.0, emissive=(0, 0, 0)):
    return f'''
        def Material "{name}"
        {{
            token outputs:surface.connect = </World/Looks/{name}/Surface.outputs:surface>
            def Shader "Surface"
            {{
                uniform token info:id = "UsdPreviewSurface"
                color3f inputs:diffuseColor = ({diffuse[0]}, {diffuse[1]}, {diffuse[2]})
                color3f inputs:emissiveColor = ({emissive[0]}, {emissive[1]}, {emissive[2]})
                float inputs:roughness = {roughness}
                float inputs:metallic = {metallic}
                token outputs:surface
            }}
        }}'''


sp, sn, sc, si = sphere(50)
bp, bc, bi = box(80)
ground = [(-1000, 0, 1000), (1000, 0, 1000), (1000, 0, -1000), (-1000, 0, -1000)]

text = f'''{world_header("Obscura demo scene: a ground plane, a rough red sphere, a polished gold sphere and a box under a sun and a sphere light.")}    def Scope "Looks"
    {{{material("Ground", (0.5, 0.5, 0.5), 0.8)}{material("Red", (0.7, 0.08, 0.05), 0.45)}{material("Gold", (1.0, 0.78, 0.34), 0.25, 1.0)}{material("Glow", (0.05, 0.05, 0.05), 0.6, 0.0, (0.4, 1.2, 2.0))}
    }}

    def Mesh "Ground" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {{
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = {fmt(ground)}
        normal3f[] normals = [(0, 1, 0)] (
            interpolation = "constant"
        )
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Ground>
    }}

    def Mesh "RedSphere" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {{
        double3 xformOp:translate = (0, 50, 0)
        uniform token[] xformOpOrder = ["xformOp:translate"]
        int[] faceVertexCounts = {ints(sc)}
        int[] faceVertexIndices = {ints(si)}
        point3f[] points = {fmt(sp)}
        normal3f[] normals = {fmt(sn)} (
            interpolation = "vertex"
        )
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Red>
    }}

    def Mesh "GoldSphere" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {{
        double3 xformOp:translate = (125, 40, -40)
        float3 xformOp:scale = (0.8, 0.8, 0.8)
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:scale"]
        int[] faceVertexCounts = {ints(sc)}
        int[] faceVertexIndices = {ints(si)}
        point3f[] points = {fmt(sp)}
        normal3f[] normals = {fmt(sn)} (
            interpolation = "vertex"
        )
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Gold>
    }}

    def Mesh "Box" (
        prepend apiSchemas = ["MaterialBindingAPI"]
    )
    {{
        double3 xformOp:translate = (-125, 40, 10)
        float xformOp:rotateY = 30
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateY"]
        int[] faceVertexCounts = {ints(bc)}
        int[] faceVertexIndices = {ints(bi)}
        point3f[] points = {fmt(bp)}
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Glow>
    }}

    def DistantLight "Sun"
    {{
        float inputs:angle = 0.53
        float inputs:intensity = 2.5
        bool inputs:normalize = 1
        color3f inputs:color = (1, 0.95, 0.88)
        float3 xformOp:rotateXYZ = (-50, 35, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }}

    def DomeLight "Sky"
    {{
        float inputs:intensity = 0.35
        color3f inputs:color = (0.75, 0.85, 1.0)
    }}

    def SphereLight "Bulb"
    {{
        float inputs:radius = 10
        float inputs:intensity = 400
        color3f inputs:color = (1, 0.7, 0.4)
        double3 xformOp:translate = (-40, 160, 140)
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}

    def Camera "Camera"
    {{
        float focalLength = 35
        float horizontalAperture = 36
        float verticalAperture = 24
        float2 clippingRange = (10, 10000)
        double3 xformOp:translate = (0, 150, 520)
        float xformOp:rotateX = -12
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateX"]
    }}
}}
'''
with open("demo.usda", "w") as f:
    f.write(text)
