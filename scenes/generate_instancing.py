#!/usr/bin/env python3
"""Writes instancing.usda: a PointInstancer scattering 2,500 spheres and boxes over a ground,
with per-instance orientation and scale (one copy of each mesh, drawn with GPU instancing)."""
import math
import random

from generate_demo import box, fmt, ints, material, prototypes_scope, sphere

random.seed(7)
sp, sn, sc, si = sphere(5, 12, 24)
bp, bc, bi = box(8)
n = 2500
positions, orientations, scales, proto = [], [], [], []
for i in range(n):
    x, z = (i % 50 - 24.5) * 12, (i // 50 - 24.5) * 12
    positions.append((x + random.uniform(-3, 3), 5, z + random.uniform(-3, 3)))
    angle = random.uniform(0, math.pi)
    orientations.append("(%g, 0, %g, 0)" % (math.cos(angle / 2), math.sin(angle / 2)))
    s = random.uniform(0.6, 1.3)
    scales.append((s, s, s))
    proto.append(i % 3 // 2)

text = f'''#usda 1.0
(
    doc = "2,500 instances of two prototypes through a PointInstancer."
    defaultPrim = "World"
    metersPerUnit = 0.01
    upAxis = "Y"
)

def Xform "World"
{{
    def Scope "Looks"
    {{{material("Ground", (0.4, 0.4, 0.4), 0.9)}{material("Red", (0.7, 0.1, 0.05), 0.4)}{material("Blue", (0.1, 0.2, 0.7), 0.3)}
    }}

    def Mesh "Ground"
    {{
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = [(-400, 0, 400), (400, 0, 400), (400, 0, -400), (-400, 0, -400)]
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Ground>
    }}

    def PointInstancer "Scatter"
    {{
        rel prototypes = [</World/Scatter/Prototypes/Ball>, </World/Scatter/Prototypes/Crate>]
        int[] protoIndices = {ints(proto)}
        point3f[] positions = {fmt(positions)}
        quath[] orientations = [{", ".join(orientations)}]
        float3[] scales = {fmt(scales)}

{prototypes_scope((sp, sn, sc, si), (bp, bc, bi), "Red", "Blue")}
    }}

    def DistantLight "Sun"
    {{
        float inputs:intensity = 3
        bool inputs:normalize = 1
        float3 xformOp:rotateXYZ = (-45, 30, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }}

    def Camera "Camera"
    {{
        float focalLength = 24
        float horizontalAperture = 36
        float verticalAperture = 24
        float2 clippingRange = (1, 5000)
        double3 xformOp:translate = (0, 260, 420)
        float xformOp:rotateX = -35
        uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateX"]
    }}
}}
'''
with open("instancing.usda", "w") as f:
    f.write(text)
