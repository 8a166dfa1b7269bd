"""USD text pieces the scene generators share: chequered cards, glowing spheres and their
materials, under /World."""
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


def xform_ops(translate, rotate_z=None):
    """A translate, then optionally a rotateZ; either a constant or {time: value} samples."""
    def op(kind, name, value):
        if isinstance(value, dict):
            samples = ", ".join(f"{t}: {v}" for t, v in sorted(value.items()))
            return f"        {kind} xformOp:{name}.timeSamples = {{ {samples} }}\n"
        return f"        {kind} xformOp:{name} = {value}\n"
    text = op("double3", "translate", translate)
    order = '"xformOp:translate"'
    if rotate_z is not None:
        text += op("float", "rotateZ", rotate_z)
        order += ', "xformOp:rotateZ"'
    return text + f"        uniform token[] xformOpOrder = [{order}]\n"


def card_prim(name, translate, width, height, cells_x, cells_y, rotate_z=None):
    p, c, i, col = card(width, height, cells_x, cells_y)
    return f'''
    def Mesh "{name}"
    {{
{xform_ops(translate, rotate_z)}        int[] faceVertexCounts = {ints(c)}
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
{xform_ops(translate)}        int[] faceVertexCounts = {ints(c)}
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


# The sample scenes' light: a normalized sun from above left and a dim sky.
SUN_AND_SKY = '''    def DistantLight "Sun"
    {
        float inputs:intensity = 2
        bool inputs:normalize = 1
        float3 xformOp:rotateXYZ = (-30, 20, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }

    def DomeLight "Sky"
    {
        float inputs:intensity = 0.3
    }
'''


def world_header(doc):
    """A sample scene's layer metadata (centimetres, Y up, frame 1) and the opening of /World."""
    return f'''#usda 1.0
(
    doc = "{doc}"
    defaultPrim = "World"
    metersPerUnit = 0.01
    upAxis = "Y"
    startTimeCode = 1
    endTimeCode = 1
)

def Xform "World"
{{
'''
