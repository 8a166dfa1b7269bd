#!/usr/bin/env python3
"""Writes the glTF 2.0 test scenes of tests/import, their buffers embedded as base64:
scene.gltf, a small scene using every feature the importer maps, nonfinite.gltf, whose binary
data holds NaN and infinity where the importer must drop them, and skinned.gltf, a two-joint arm
whose elbow bends; and embedded.glb, a binary glTF whose texture is a PNG in a buffer view.

Run from this folder: python3 make_scene_gltf.py. The values here are the ones import_test.cpp expects.
"""
import base64
import json
import math
import re
import struct
import zlib

FLOAT, USHORT = 5126, 5123


class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def view(self, raw, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)}
        if target:
            view["target"] = target
        self.views.append(view)
        self.data += raw
        return len(self.views) - 1

    def add(self, fmt, values, component, kind, count, target=None, bounds=False):
        self.view(struct.pack("<" + fmt * len(values), *values), target)
        accessor = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        if bounds:
            width = len(values) // count
            columns = [values[i::width] for i in range(width)]
            accessor["min"] = [min(c) for c in columns]
            accessor["max"] = [max(c) for c in columns]
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def png_1x1(rgb):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    header = struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes([0, *rgb])))
            + chunk(b"IEND", b""))


def quat(axis, degrees):
    s = math.sin(math.radians(degrees) / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(math.radians(degrees) / 2)]


buf = Buffer()
# A unit-square quad in the XY plane facing +Z; glTF texture coordinates have their origin top-left.
positions = [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]
normals = [0, 0, 1] * 4
uvs = [0, 1, 1, 1, 1, 0, 0, 0]
colors = [1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1]
position = buf.add("f", positions, FLOAT, "VEC3", 4, 34962, bounds=True)
normal = buf.add("f", normals, FLOAT, "VEC3", 4, 34962)
uv = buf.add("f", uvs, FLOAT, "VEC2", 4, 34962)
color = buf.add("f", colors, FLOAT, "VEC4", 4, 34962)
indices = buf.add("H", [0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6, 34963)
# Three loose points: a primitive the converter drops.
point_positions = buf.add("f", [0, 0, 0, 1, 0, 0, 0, 1, 0], FLOAT, "VEC3", 3, 34962, bounds=True)
# "Parent" moves from x = 1 to x = 3 over one second.
times = buf.add("f", [0, 1], FLOAT, "SCALAR", 2, bounds=True)
moves = buf.add("f", [1, 0, 0, 3, 0, 0], FLOAT, "VEC3", 2)

scene = {
    "asset": {"version": "2.0", "generator": "Obscura tests/import/data/make_scene_gltf.py"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "scene": 0,
    "scenes": [{"nodes": [0, 3, 4, 5, 6, 7, 8, 9]}],
    "nodes": [
        {"name": "Root Group", "translation": [0, 0, -1], "rotation": quat([0, 1, 0], 90), "children": [1]},
        {"name": "Parent", "translation": [1, 0, 0], "children": [2]},
        {"name": "Child", "translation": [0, 0, 2], "mesh": 0},
        {"name": "Main Camera", "translation": [0, 1, 5], "camera": 0},
        {"name": "Sun", "rotation": quat([1, 0, 0], -90), "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "Bulb", "translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"name": "Ortho", "translation": [0, 0, 10], "camera": 1},
        {"name": "Spot", "translation": [0, 4, 0], "extensions": {"KHR_lights_punctual": {"light": 2}}},
        {"name": "Dup"},
        {"name": "Dup"},
    ],
    "meshes": [{"name": "Quad", "primitives": [
        {"attributes": {"POSITION": position, "NORMAL": normal, "TEXCOORD_0": uv, "COLOR_0": color},
         "indices": indices, "material": 0},
        {"attributes": {"POSITION": point_positions}, "mode": 0, "material": 1},
    ]}],
    "materials": [
        {"name": "Painted Metal", "doubleSided": True, "emissiveFactor": [0.5, 0.25, 0],
         "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0.7,
                                  "roughnessFactor": 0.3, "baseColorTexture": {"index": 0}}},
        {"name": "Embedded", "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}},
    ],
    "textures": [{"source": 0}, {"source": 1}],
    "images": [
        {"uri": "textures/checker.png"},
        {"uri": "data:image/png;base64," + base64.b64encode(png_1x1([255, 128, 0])).decode()},
    ],
    "cameras": [
        {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1, "zfar": 100}},
        {"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.01, "zfar": 50}},
    ],
    "extensions": {"KHR_lights_punctual": {"lights": [
        {"name": "Sun", "type": "directional", "color": [1, 0.5, 0.25], "intensity": 3},
        {"name": "Bulb", "type": "point", "color": [1, 1, 1], "intensity": 20},
        {"name": "Spot", "type": "spot", "intensity": 5, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
    ]}},
    "animations": [{"name": "Move",
                    "samplers": [{"input": times, "output": moves, "interpolation": "LINEAR"}],
                    "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}]}],
}



def embed(gltf, buffer):
    gltf["accessors"] = buffer.accessors
    gltf["bufferViews"] = buffer.views
    gltf["buffers"] = [{"byteLength": len(buffer.data),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buffer.data)).decode()}]


def write(path, gltf):
    text = json.dumps(gltf, indent=1)
    # Lists of numbers on one line keep the file readable.
    text = re.sub(r"\[[-0-9.e,\s]*\]", lambda m: " ".join(m.group(0).split()), text)
    with open(path, "w") as out:
        out.write(text + "\n")


embed(scene, buf)
write("scene.gltf", scene)

nan, inf = float("nan"), float("inf")
bad = Buffer()
triangle = bad.add("f", [0, 0, 0, 1, 0, 0, 0, 1, 0], FLOAT, "VEC3", 3, 34962, bounds=True)
bad_normals = bad.add("f", [0, 0, 1, nan, 0, 1, 0, 0, 1], FLOAT, "VEC3", 3, 34962)
bad_uvs = bad.add("f", [0, 0, inf, 0, 0, 1], FLOAT, "VEC2", 3, 34962)
bad_points = bad.add("f", [0, 0, 0, nan, 0, 0, 0, 1, 0], FLOAT, "VEC3", 3, 34962)
bad.accessors[bad_points].update({"min": [0, 0, 0], "max": [0, 1, 0]})
key_times = bad.add("f", [0, 1], FLOAT, "SCALAR", 2, bounds=True)
key_moves = bad.add("f", [0, 0, 0, nan, 0, 0], FLOAT, "VEC3", 2)
nonfinite = {
    "asset": {"version": "2.0", "generator": "Obscura tests/import/data/make_scene_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "Holder", "mesh": 0}],
    "meshes": [{"name": "Broken", "primitives": [
        {"attributes": {"POSITION": triangle, "NORMAL": bad_normals, "TEXCOORD_0": bad_uvs}},
        {"attributes": {"POSITION": bad_points}},
    ]}],
    "animations": [{"samplers": [{"input": key_times, "output": key_moves}],
                    "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}],
}
embed(nonfinite, bad)
write("nonfinite.gltf", nonfinite)

# A two-joint arm: joint Shoulder at (0, 10, 0), its child Elbow 1 along X. The elbow turns about +Z
# from 0 to 90 degrees over the first second. Point 0 follows the shoulder, point 1 the elbow,
# point 2 both halves each. The mesh's node is moved 100 along X, which a skinned mesh ignores.
arm = Buffer()
arm_points = arm.add("f", [0.5, 10, 0, 2, 10, 0, 1.5, 10, 0], FLOAT, "VEC3", 3, 34962, bounds=True)
arm_joints = arm.add("H", [0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0], USHORT, "VEC4", 3, 34962)
arm_weights = arm.add("f", [1, 0, 0, 0, 1, 0, 0, 0, 0.5, 0.5, 0, 0], FLOAT, "VEC4", 3, 34962)
# Inverse bind matrices (column-major): the joints' world transforms at bind, inverted.
inverse_binds = arm.add("f", [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -10, 0, 1,
                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -1, -10, 0, 1], FLOAT, "MAT4", 2)
bend_times = arm.add("f", [0, 1], FLOAT, "SCALAR", 2, bounds=True)
bend = arm.add("f", quat([0, 0, 1], 0) + quat([0, 0, 1], 90), FLOAT, "VEC4", 2)
skinned = {
    "asset": {"version": "2.0", "generator": "Obscura tests/import/data/make_scene_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [
        {"name": "Arm", "mesh": 0, "skin": 0, "translation": [100, 0, 0]},
        {"name": "Shoulder", "translation": [0, 10, 0], "children": [2]},
        {"name": "Elbow", "translation": [1, 0, 0]},
    ],
    "meshes": [{"name": "Arm", "primitives": [{"attributes": {"POSITION": arm_points, "JOINTS_0": arm_joints,
                                                              "WEIGHTS_0": arm_weights}}]}],
    "skins": [{"joints": [1, 2], "inverseBindMatrices": inverse_binds}],
    "animations": [{"name": "Bend", "samplers": [{"input": bend_times, "output": bend}],
                    "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}],
}
embed(skinned, arm)
write("skinned.gltf", skinned)

# The quad of scene.gltf as a binary glTF (GLB): its image is a PNG stored in a buffer view of the
# file's binary chunk, which the importer writes out as it does a data: URI.
glb = Buffer()
glb_positions = glb.add("f", positions, FLOAT, "VEC3", 4, 34962, bounds=True)
glb_uvs = glb.add("f", uvs, FLOAT, "VEC2", 4, 34962)
glb_indices = glb.add("H", [0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6, 34963)
glb_image = glb.view(png_1x1([0, 64, 255]))
binary = {
    "asset": {"version": "2.0", "generator": "Obscura tests/import/data/make_scene_gltf.py"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "Card", "mesh": 0}],
    "meshes": [{"name": "Card", "primitives": [
        {"attributes": {"POSITION": glb_positions, "TEXCOORD_0": glb_uvs}, "indices": glb_indices, "material": 0}]}],
    "materials": [{"name": "Packed", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "textures": [{"source": 0}],
    "images": [{"bufferView": glb_image, "mimeType": "image/png"}],
    "accessors": glb.accessors,
    "bufferViews": glb.views,
    "buffers": [{"byteLength": len(glb.data)}],
}


def write_glb(path, gltf, data):
    # GLB 2.0: a 12-byte header, then a JSON chunk padded with spaces and a BIN chunk padded with
    # zeros, each 4-byte aligned.
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data = bytes(data) + b"\0" * (-len(data) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    with open(path, "wb") as out:
        out.write(struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks)


write_glb("embedded.glb", binary, glb.data)
