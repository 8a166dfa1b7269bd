"""The evaluated depsgraph as Obscura prims, kept in an ``obscura.Delegate``'s in-memory scene.

``SceneSync.sync`` translates a whole depsgraph (a final render, the first viewport draw);
``SceneSync.update`` takes a depsgraph's updates (RenderEngine.view_update) and marks dirty only
the prims of the objects that changed, with the dirty bits of what changed (transform, geometry,
material, light, camera), as hdEmbree's prims sync only what their bits say.

Prim paths (names escaped one to one by prim_name): /Objects/<object> (a mesh of several
materials: one prim per material, /Objects/<object>/m<slot>), /Instancers/<parent>/<object> with
the instanced mesh under /Prototypes/<object>, /Looks/<material>, /Lights/<object>, /Camera, /World.
"""

from __future__ import annotations

import logging

import bpy
import numpy as np

import obscura

from . import convert, materials

CAMERA = convert.CAMERA_PATH
WORLD = "/World"
DEFAULT_LOOK = "/Looks/_default"
# Blender's surface without a material: white-ish diffuse (Cycles' default surface is 0.8 grey).
DEFAULT_LOOK_VALUES = {"inputs:diffuseColor": (0.8, 0.8, 0.8), "inputs:roughness": 0.5}
_GEOMETRY_TYPES = {"MESH", "CURVE", "SURFACE", "FONT", "META"}
_FACE_VARYING = {"normals": obscura.Interpolation.FACE_VARYING, "primvars:st": obscura.Interpolation.FACE_VARYING}


def prim_name(name: str) -> str:
    """A Blender name as a USD prim name (letters, digits, underscores; no leading digit), one to
    one: every other character, an underscore and a leading digit become _<hex code>_, so
    "Cube.001" and "Cube_001" stay two prims."""
    def escaped(i: int, c: str) -> str:
        plain = c.isascii() and (c.isalpha() or (c.isdigit() and i > 0))
        return c if plain else f"_{ord(c):X}_"

    return "".join(escaped(i, c) for i, c in enumerate(name)) or "_"


def mesh_parts(obj) -> list[tuple[int, dict]]:
    """(material slot, mesh values) per material the evaluated object's triangles use: triangulated
    loops (Mesh.loop_triangles) with the split normals and the active UV map face-varying."""
    mesh = obj.to_mesh()
    try:
        if mesh is None or not mesh.polygons:
            return []
        mesh.calc_loop_triangles()
        if hasattr(mesh, "calc_normals_split"):  # Blender < 4.1 computes split normals on request
            mesh.calc_normals_split()
        points = np.empty(len(mesh.vertices) * 3, np.float32)
        mesh.vertices.foreach_get("co", points)
        triangles = len(mesh.loop_triangles)
        corners = np.empty(triangles * 3, np.int32)
        mesh.loop_triangles.foreach_get("loops", corners)
        vertices = np.empty(triangles * 3, np.int32)
        mesh.loop_triangles.foreach_get("vertices", vertices)
        slots = np.empty(triangles, np.int32)
        mesh.loop_triangles.foreach_get("material_index", slots)
        normals = np.empty(len(mesh.loops) * 3, np.float32)
        mesh.loops.foreach_get("normal", normals)
        normals = normals.reshape(-1, 3)
        uv_layer = mesh.uv_layers.active
        uvs = None
        if uv_layer is not None:
            uvs = np.empty(len(mesh.loops) * 2, np.float32)
            uv_layer.data.foreach_get("uv", uvs)
            uvs = uvs.reshape(-1, 2)
        parts = []
        for slot in np.unique(slots):
            chosen = np.repeat(slots == slot, 3)
            loops = corners[chosen]
            values = {"points": points.reshape(-1, 3), "faceVertexCounts": np.full(len(loops) // 3, 3, np.int32),
                      "faceVertexIndices": vertices[chosen], "normals": normals[loops],
                      "subdivisionScheme": "none"}
            if uvs is not None:
                values["primvars:st"] = uvs[loops]
            parts.append((int(slot), values))
        return parts
    finally:
        obj.to_mesh_clear()


class ShutterScene(obscura.Scene):
    """The in-memory scene, with transforms sampled over the shutter where the add-on recorded
    them (``samples``: path -> [(time code, GfMatrix4d numbers)], sorted by time)."""

    def __init__(self) -> None:
        super().__init__()
        self.samples: dict[str, list] = {}

    def sample_transform(self, path, time0, time1, max_samples):
        # The recorded samples inside [time0, time1] (the delegate asks [t, t] for the frame's own).
        eps = 1e-6
        inside = [s for s in self.samples.get(path, []) if time0 - eps <= s[0] <= time1 + eps]
        if not inside or len(inside) > max_samples:
            return super().sample_transform(path, time0, time1, max_samples)
        return inside


class SceneSync:
    """Owns the prims of one Blender scene in ``delegate`` (whose scene is an ``obscura.Scene``)."""

    def __init__(self, delegate: obscura.Delegate, logger: logging.Logger):
        self.delegate = delegate
        self.logger = logger
        self.object_prims: dict[str, list[str]] = {}  # original object name -> its prim paths
        self.pass_index: dict[str, int] = {}  # mesh prim path -> Object.pass_index
        self.warned: set[str] = set()  # materials already warned about
        self.warnings: list[str] = []
        self.materials: set[str] = set()
        self.camera_object_name: str | None = None

    # --- prims in the delegate -------------------------------------------------------------------

    def put(self, type: str, path: str, values: dict, transform=None, interpolations=None) -> None:
        """Inserts the prim, or replaces its values and marks all of it dirty."""
        d = self.delegate
        if path in d.scene.prims:
            d.scene.add(type, path, values, transform, interpolations)
            d.mark_dirty(path, obscura.Dirty.ALL)
        else:
            d.insert_prim(type, path, values, transform=transform, interpolations=interpolations)

    def _remove(self, path: str) -> None:
        if path in self.delegate.scene.prims:
            self.delegate.remove_prim(path)
        self.pass_index.pop(path, None)

    def _remove_object(self, name: str) -> None:
        for path in self.object_prims.pop(name, []):
            self._remove(path)

    def _warn(self, key: str, message: str) -> None:
        if key not in self.warned:
            self.warned.add(key)
            self.warnings.append(message)
            self.logger.warning("%s", message)

    # --- translation ------------------------------------------------------------------------------

    def material_path(self, material) -> str:
        if material is None:
            if DEFAULT_LOOK not in self.materials:
                self.put("material", DEFAULT_LOOK, DEFAULT_LOOK_VALUES)
                self.materials.add(DEFAULT_LOOK)
            return DEFAULT_LOOK
        path = "/Looks/" + prim_name(material.name)
        if path not in self.materials:
            self._sync_material(material, path)
        return path

    def _sync_material(self, material, path: str) -> None:
        values, warning = materials.material_values(material)
        if warning:
            self._warn(material.name, warning)
        if material.blend_method == "CLIP":
            values["inputs:opacityThreshold"] = float(material.alpha_threshold)
        self.put("material", path, values)
        self.materials.add(path)

    def _mesh_prims(self, obj, base: str, transform) -> list[str]:
        """The evaluated object's mesh prims under ``base``."""
        parts = mesh_parts(obj)
        paths = []
        for slot, values in parts:
            path = base if len(parts) == 1 else f"{base}/m{slot}"
            material = obj.material_slots[slot].material if slot < len(obj.material_slots) else None
            values["material:binding"] = obscura.Path(self.material_path(material))
            self.put("mesh", path, values, transform, _FACE_VARYING)
            self.pass_index[path] = obj.pass_index
            paths.append(path)
        return paths

    def _light(self, obj, path: str, matrix) -> None:
        light = obj.data
        prim_type, values = convert.light_values(
            light_type=light.type, energy=light.energy, color=light.color, specular=light.specular_factor,
            diffuse=getattr(light, "diffuse_factor", 1.0), use_shadow=light.use_shadow,
            angle=getattr(light, "angle", 0.0), radius=getattr(light, "shadow_soft_size", 0.0),
            spot_size=getattr(light, "spot_size", 0.0), spot_blend=getattr(light, "spot_blend", 0.0),
            shape=getattr(light, "shape", "SQUARE"), size=getattr(light, "size", 0.0),
            size_y=getattr(light, "size_y", 0.0))
        self.put(prim_type, path, values, convert.usd_matrix(matrix))

    def camera_values(self, depsgraph, width: int, height: int) -> tuple[dict, list[float]] | None:
        """The scene camera's values and transform for an image of width x height."""
        scene = depsgraph.scene
        if scene.camera is None:
            return None
        obj = scene.camera.evaluated_get(depsgraph)
        cam = obj.data
        dof = cam.dof
        fstop = focus = None
        if dof.use_dof:
            fstop = dof.aperture_fstop
            if dof.focus_object is not None:
                target = dof.focus_object.evaluated_get(depsgraph).matrix_world.translation
                focus = convert.focus_distance_to(obj.matrix_world, target)
            else:
                focus = dof.focus_distance
        values = convert.camera_values(
            kind=cam.type, lens=cam.lens, ortho_scale=cam.ortho_scale, sensor_fit=cam.sensor_fit,
            sensor_width=cam.sensor_width, sensor_height=cam.sensor_height, shift_x=cam.shift_x,
            shift_y=cam.shift_y, clip_start=cam.clip_start, clip_end=cam.clip_end, width=width, height=height,
            meters_per_unit=self.meters_per_unit(scene), fstop=fstop, focus_distance=focus or 0.0,
            blades=dof.aperture_blades, rotation=dof.aperture_rotation)
        return values, convert.usd_matrix(obj.matrix_world)

    @staticmethod
    def meters_per_unit(scene) -> float:
        return float(scene.unit_settings.scale_length) if scene.unit_settings.system != "NONE" else 1.0

    def _world(self, scene) -> None:
        world = scene.world
        if world is None:
            self._remove(WORLD)
            return
        color, strength, texture = tuple(world.color), 1.0, None
        if world.use_nodes and world.node_tree:
            output = world.node_tree.get_output_node("ALL")
            background = materials.linked_node(output.inputs["Surface"]) if output else None
            if background is not None and background.bl_idname == "ShaderNodeBackground":
                color = tuple(background.inputs["Color"].default_value)[:3]
                strength = float(background.inputs["Strength"].default_value)
                env = materials.linked_node(background.inputs["Color"])
                if env is not None and env.bl_idname == "ShaderNodeTexEnvironment" and env.image is not None:
                    texture = materials.image_file(env)
                elif env is not None:
                    self._warn("world:" + world.name, f"world {world.name!r}: a {env.bl_label} node on the "
                               "Background colour; rendered with the Background node's colour")
            elif background is not None:
                self._warn("world:" + world.name, f"world {world.name!r}: a {background.bl_label} node on the "
                           "World Output; rendered with the world's viewport colour")
        # A world's background is radiance (Cycles: Color x Strength): the dome's nits.
        values = {"inputs:intensity": strength, "inputs:color": color[:3]}
        if texture:
            values.update({"inputs:texture:file": texture, "inputs:texture:format": "latlong",
                           "inputs:color": (1.0, 1.0, 1.0)})
        # Blender's world +Z is up; the dome's latlong top pole is its local +Y: rotate +Y onto +Z.
        self.put("domeLight", WORLD, values, [1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1])

    def _instances(self, depsgraph) -> dict[str, list]:
        """Instances grouped by instancer (parent object and instanced object) -> [(object, matrix)]."""
        groups: dict[str, list] = {}
        for instance in depsgraph.object_instances:
            if instance.is_instance and instance.object.type in _GEOMETRY_TYPES:
                parent = instance.parent.original.name if instance.parent else "_"
                key = f"{prim_name(parent)}/{prim_name(instance.object.original.name)}"
                groups.setdefault(key, []).append((instance.object, instance.matrix_world.copy()))
        return groups

    def _instancer(self, key: str, members: list) -> list[str]:
        obj = members[0][0]
        prototypes = self._mesh_prims(obj, "/Prototypes/" + key, None)
        if not prototypes:
            return []
        positions, orientations, scales, indices = [], [], [], []
        for _, matrix in members:
            t, q, s = matrix.decompose()
            for i in range(len(prototypes)):
                positions.append(tuple(t))
                orientations.append((q.w, q.x, q.y, q.z))  # real part first, as USD writes quaternions
                scales.append(tuple(s))
                indices.append(i)
        path = "/Instancers/" + key
        self.put("instancer", path, {"prototypes": [obscura.Path(p) for p in prototypes],
                                      "protoIndices": np.array(indices, np.int32),
                                      "positions": np.array(positions, np.float32),
                                      "orientations": np.array(orientations, np.float32),
                                      "scales": np.array(scales, np.float32)})
        return prototypes + [path]

    def _object(self, depsgraph, obj) -> None:
        """(Re)translates one evaluated, non-instanced object."""
        name = obj.original.name
        self._remove_object(name)
        if obj.type in _GEOMETRY_TYPES:
            self.object_prims[name] = self._mesh_prims(obj, "/Objects/" + prim_name(name),
                                                       convert.usd_matrix(obj.matrix_world))
        elif obj.type == "LIGHT":
            path = "/Lights/" + prim_name(name)
            self._light(obj, path, obj.matrix_world)
            self.object_prims[name] = [path]

    def world_matrices(self, depsgraph) -> dict[str, list[float]]:
        """The world transform of every prim of a non-instanced object and of the camera, now."""
        matrices = {}
        for instance in depsgraph.object_instances:
            if not instance.is_instance:
                matrix = convert.usd_matrix(instance.object.matrix_world)
                for path in self.object_prims.get(instance.object.original.name, []):
                    matrices[path] = matrix
        if depsgraph.scene.camera is not None:
            matrices[CAMERA] = convert.usd_matrix(depsgraph.scene.camera.evaluated_get(depsgraph).matrix_world)
        return matrices

    def sync(self, depsgraph, width: int, height: int) -> None:
        """Translates the whole depsgraph: every visible object, instance, the camera and world."""
        scene = depsgraph.scene
        self.delegate.set_render_settings(metersPerUnit=self.meters_per_unit(scene),
                                          timeCodesPerSecond=scene.render.fps / scene.render.fps_base)
        for name in list(self.object_prims):
            self._remove_object(name)
        for path in list(self.materials):
            self._remove(path)
        self.materials.clear()
        for instance in depsgraph.object_instances:
            if not instance.is_instance:
                self._object(depsgraph, instance.object)
        for key, members in self._instances(depsgraph).items():
            self.object_prims["instancer:" + key] = self._instancer(key, members)
        self._world(scene)
        self.sync_camera(depsgraph, width, height)

    def sync_camera(self, depsgraph, width: int, height: int) -> bool:
        camera = self.camera_values(depsgraph, width, height)
        if camera is None:
            return False
        self.put("camera", CAMERA, camera[0], camera[1])
        return True

    def update(self, depsgraph) -> int:
        """Applies a depsgraph's updates; returns the number of prims marked dirty."""
        d = self.delegate
        dirtied = 0
        resync_all = False
        for update in depsgraph.updates:
            id_ = update.id
            if isinstance(id_, bpy.types.Material):
                path = "/Looks/" + prim_name(id_.original.name)
                if path in self.materials:
                    self._sync_material(id_.original, path)
                    dirtied += 1
            elif isinstance(id_, bpy.types.World):
                self._world(depsgraph.scene)
                dirtied += 1
            elif isinstance(id_, bpy.types.Object):
                name = id_.original.name
                instancer_key = "instancer:" + prim_name(name) + "/"
                if id_.is_instancer or any(k.startswith(instancer_key) for k in self.object_prims):
                    resync_all = True  # what it instances may have changed as a whole
                elif update.is_updated_geometry or name not in self.object_prims:
                    self._object(depsgraph, id_)
                    dirtied += len(self.object_prims.get(name, []))
                elif update.is_updated_transform:
                    matrix = convert.usd_matrix(id_.matrix_world)
                    for path in self.object_prims[name]:
                        d.set_transform(path, matrix)
                        dirtied += 1
            elif isinstance(id_, bpy.types.Collection) or isinstance(id_, bpy.types.Scene):
                # Objects added, removed, hidden: the set of instances changed.
                if update.is_updated_geometry or isinstance(id_, bpy.types.Collection):
                    resync_all = True
        if resync_all:
            self._resync_membership(depsgraph)
            dirtied += 1
        return dirtied

    def _resync_membership(self, depsgraph) -> None:
        """Objects gone or hidden are removed, new ones added, instancers rebuilt."""
        present = {i.object.original.name for i in depsgraph.object_instances if not i.is_instance}
        for name in [n for n in self.object_prims if n not in present or n.startswith("instancer:")]:
            self._remove_object(name)
        for instance in depsgraph.object_instances:
            if not instance.is_instance and instance.object.original.name not in self.object_prims:
                self._object(depsgraph, instance.object)
        for key, members in self._instances(depsgraph).items():
            self.object_prims["instancer:" + key] = self._instancer(key, members)
