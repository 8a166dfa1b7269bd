#!/usr/bin/env python3
"""Writes occlusion_hall.usda, occlusion culling's benchmark (seed 004 "Occlusion culling"): a hall
of 12,000 instanced props (three balls of 1,152 triangles to each crate of 12: 10.4 million
triangles in all) behind a wall with a doorway, 40 more props in front of it, seen from in front of
the wall. Through the doorway the
camera sees a narrow wedge of the hall; the wall hides the rest. Run from this folder; the output
is committed."""
from generate_demo import box, fmt, ints, material, prototypes_scope, sphere
from usda_pieces import world_header

ball = sphere(15, 24, 24)  # 24 x 24 quads: 1,152 triangles
crate = box(24)
columns, rows = 120, 100
hall = [(-2975 + 50 * i, 15, -1000 - 100 * j) for j in range(rows) for i in range(columns)]
front = [(-390 + 20 * i, 15, -300 - 40 * (i % 4)) for i in range(40)]
positions = hall + front
proto = [i % 4 // 3 for i in range(len(positions))]  # three balls to each crate


def wall_box(name, lo, hi):
    """A box mesh between corners `lo` and `hi`, in the wall's material."""
    size = tuple(hi[k] - lo[k] for k in range(3))
    centre = tuple((hi[k] + lo[k]) / 2 for k in range(3))
    points, counts, indices = box(1)
    points = [tuple(p[k] * size[k] + centre[k] for k in range(3)) for p in points]
    return f'''
    def Mesh "{name}"
    {{
        int[] faceVertexCounts = {ints(counts)}
        int[] faceVertexIndices = {ints(indices)}
        point3f[] points = {fmt(points)}
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Wall>
    }}
'''


text = f'''{world_header("Occlusion culling benchmark: 12,000 instanced props (10.4 million triangles) in a hall behind a wall with a doorway, 40 in front of it.")}    def Scope "Looks"
    {{{material("Ground", (0.4, 0.4, 0.4), 0.9)}{material("Wall", (0.6, 0.55, 0.5), 0.8)}{material("Red", (0.7, 0.1, 0.05), 0.4)}{material("Blue", (0.1, 0.2, 0.7), 0.3)}
    }}

    def Mesh "Ground"
    {{
        int[] faceVertexCounts = [4]
        int[] faceVertexIndices = [0, 1, 2, 3]
        point3f[] points = [(-10000, 0, 10000), (10000, 0, 10000), (10000, 0, -12000), (-10000, 0, -12000)]
        uniform token subdivisionScheme = "none"
        rel material:binding = </World/Looks/Ground>
    }}
{wall_box("WallLeft", (-4000, 0, -820), (-100, 1500, -800))}{wall_box("WallRight", (100, 0, -820), (4000, 1500, -800))}{wall_box("Lintel", (-100, 300, -820), (100, 1500, -800))}
    def PointInstancer "Props"
    {{
        rel prototypes = [</World/Props/Prototypes/Ball>, </World/Props/Prototypes/Crate>]
        int[] protoIndices = {ints(proto)}
        point3f[] positions = {fmt(positions)}

{prototypes_scope(ball, crate, "Red", "Blue")}
    }}

    def DistantLight "Sun"
    {{
        float inputs:intensity = 3
        bool inputs:normalize = 1
        float3 xformOp:rotateXYZ = (-50, 30, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }}

    def Camera "Camera"
    {{
        float focalLength = 24
        float horizontalAperture = 36
        float verticalAperture = 20.25
        float2 clippingRange = (1, 20000)
        double3 xformOp:translate = (0, 170, 0)
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }}
}}
'''
with open("occlusion_hall.usda", "w") as f:
    f.write(text)
