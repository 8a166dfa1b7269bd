#!/usr/bin/env python3
"""Writes sky.hdr, a small procedural latlong sky (Radiance RGBE, 256x128), and dome_texture.usda:
the demo scene with its constant sky replaced by that texture. Run from this folder; the outputs are
committed. Layout: UsdLux latlong (OpenEXR's latitude-longitude map): +Y up, longitude 0 along +Z,
+pi/2 along +X, the left edge at longitude +pi, the top row at latitude +pi/2."""
import math

WIDTH, HEIGHT = 256, 128
# Towards the demo's sun (its DistantLight, rotateXYZ (-50, 35, 0), emits along (-0.369, -0.766, -0.527)).
SUN = (0.369, 0.766, 0.527)


def radiance(d):
    """Sky radiance in nits: blue at the zenith, paler at the horizon, a glow around the sun
    (the sun itself is the demo's DistantLight), dark warm ground below the horizon."""
    if d[1] < 0:
        return (0.08, 0.07, 0.06)
    t = d[1] ** 0.5
    zenith, horizon = (0.12, 0.22, 0.48), (0.55, 0.6, 0.68)
    sky = [h + (z - h) * t for z, h in zip(zenith, horizon)]
    glow = max(0.0, sum(a * b for a, b in zip(d, SUN))) ** 32 * 4.0
    return tuple(c + glow * w for c, w in zip(sky, (1.0, 0.9, 0.7)))


def rgbe(rgb):
    v = max(rgb)
    if v < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(v)
    scale = mantissa * 256.0 / v
    return bytes([min(255, int(c * scale)) for c in rgb] + [exponent + 128])


def write_sky(path):
    rows = []
    for y in range(HEIGHT):
        latitude = math.pi * (0.5 - (y + 0.5) / HEIGHT)
        for x in range(WIDTH):
            longitude = math.pi * (1.0 - 2.0 * (x + 0.5) / WIDTH)
            d = (math.cos(latitude) * math.sin(longitude), math.sin(latitude),
                 math.cos(latitude) * math.cos(longitude))
            rows.append(rgbe(radiance(d)))
    header = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (HEIGHT, WIDTH)
    with open(path, "wb") as f:
        f.write(header + b"".join(rows))  # flat (not run-length encoded) scanlines


SCENE = '''#usda 1.0
(
    doc = "The demo scene under a textured sky dome (generate_dome_texture.py writes this file and sky.hdr)."
    defaultPrim = "World"
    subLayers = [@demo.usda@]
)

over "World"
{
    over "Sky"
    {
        asset inputs:texture:file = @sky.hdr@
        token inputs:texture:format = "latlong"
        float inputs:intensity = 1
        color3f inputs:color = (1, 1, 1)
    }
}
'''

if __name__ == "__main__":
    write_sky("sky.hdr")
    with open("dome_texture.usda", "w") as f:
        f.write(SCENE)
