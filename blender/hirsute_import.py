# Hirsute's scene file for Blender (`hirsute export --blender FILE`, docs/export.md) imported
# into a ready scene: the plant's surfaces as meshes with the principled BSDF, its hairs, fur
# strands, feather barbs and lines as hair curves (Blender's Curves objects, a radius and a
# colour at each point) with Cycles' principled hair BSDF, and the view file's camera and lights.
#
# Installed from Blender's preferences (Add-ons > Install…), it adds File > Import > Hirsute.
# Run headless, it imports a file and saves and/or renders it:
#
#   blender -b --python hirsute_import.py -- FILE [--save OUT.blend]
#                                              [--render OUT.png --samples N --seed S --size WxH]
#
# Written for Blender 3.4 (Debian 12's), whose Python API cannot size a Curves datablock: each
# curve group is made a mesh of edge chains carrying the radius and colour as point attributes,
# and geometry nodes' Mesh to Curve, applied by Convert > Curves, turns it into Curves that keep
# both. Only the standard library is used (Debian's Blender comes without numpy).

bl_info = {
    "name": "Hirsute scene",
    "author": "Hirsute",
    "version": (1, 0, 0),
    "blender": (3, 4, 0),
    "location": "File > Import > Hirsute scene (.hirsute)",
    "description": "Imports a plant exported by `hirsute export --blender`: meshes, hair "
                   "curves, camera and lights",
    "category": "Import-Export",
}

import array
import json
import math
import os
import struct
import sys

import bpy
from mathutils import Matrix, Vector

MAGIC = b"HIRSUTEB"
VERSION = 1
FOOTER_BYTES = 24  # index offset (uint64), index length (uint64), magic
POINT_FLOATS = 7   # x y z radius r g b

# How strong a light of colour 1 is: Cycles' sun of strength π lights a white diffuse surface
# facing it to 1, as GL's light of diffuse colour 1 does.
SUN_STRENGTH = math.pi


class HirsuteFileError(Exception):
    pass


def read_index(path):
    """The file's bytes and its JSON index, checked (docs/export.md, "The scene for Blender")."""
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 16 + FOOTER_BYTES or data[:8] != MAGIC or data[-8:] != MAGIC:
        raise HirsuteFileError("not a Hirsute scene for Blender (no HIRSUTEB at its ends)")
    version, = struct.unpack_from("<I", data, 8)
    if version != VERSION:
        raise HirsuteFileError(
            f"version {version} of the scene; this add-on reads version {VERSION}")
    offset, length = struct.unpack_from("<QQ", data, len(data) - FOOTER_BYTES)
    if offset < 16 or offset + length != len(data) - FOOTER_BYTES:
        raise HirsuteFileError("the index is not where the footer says")
    try:
        index = json.loads(data[offset:offset + length].decode("utf-8"))
    except ValueError as error:
        raise HirsuteFileError(f"the index is not JSON: {error}") from None
    if index.get("format") != "hirsute-blender":
        raise HirsuteFileError("the index is not a Hirsute scene's")
    return data, index


def values(data, kind, offset, count):
    """`count` 4-byte numbers of type `kind` at `offset`, which must lie among the arrays (between
    the header and the index): a file that says otherwise is refused, not read past."""
    end = len(data) - FOOTER_BYTES
    if not (isinstance(offset, int) and isinstance(count, int) and 16 <= offset
            and count >= 0 and offset + 4 * count <= end):
        raise HirsuteFileError(f"an array of {count} numbers at byte {offset} is not in the file")
    result = array.array(kind)
    result.frombytes(data[offset:offset + 4 * count])
    if sys.byteorder != "little":
        result.byteswap()
    return result


def floats(data, offset, count):
    return values(data, "f", offset, count)


def uints(data, offset, count):
    return values(data, "I", offset, count)


def shininess_to_roughness(shininess):
    # A Blinn–Phong exponent n as a microfacet roughness: α² = 2 / (n + 2) (Walter et al. 2007).
    return max(0.05, min(1.0, math.sqrt(2.0 / (max(shininess, 0.0) + 2.0))))


def make_material(entry, coloured):
    """A principled BSDF (surfaces) or principled hair BSDF (curves) of an index entry; with
    `coloured`, the colour comes from the geometry's "colour" attribute."""
    name = entry["name"] + ("_coloured" if coloured and entry["shading"] == "surface" else "")
    material = bpy.data.materials.new("hirsute_" + name)
    material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    output = nodes.new("ShaderNodeOutputMaterial")
    diffuse = tuple(entry["diffuse"]) + (1.0,)
    if entry["shading"] == "hair":
        bsdf = nodes.new("ShaderNodeBsdfHairPrincipled")
        bsdf.parametrization = "COLOR"
        bsdf.inputs["Color"].default_value = diffuse
        bsdf.inputs["Roughness"].default_value = 0.3
        bsdf.inputs["Radial Roughness"].default_value = 0.3
        attribute = nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = "colour"
        links.new(attribute.outputs["Color"], bsdf.inputs["Color"])
        links.new(bsdf.outputs[0], output.inputs["Surface"])
        material.diffuse_color = diffuse
        return material
    bsdf = nodes.new("ShaderNodeBsdfPrincipled")
    bsdf.inputs["Base Color"].default_value = diffuse
    bsdf.inputs["Roughness"].default_value = shininess_to_roughness(entry["shininess"])
    # GL's specular colour scales its highlight from none (0) to the light's colour (1); the
    # principled BSDF's Specular 0.5 is the 4% reflectance of most dielectrics: the colour's
    # display value (the file's is linear) times 0.5.
    bsdf.inputs["Specular"].default_value = 0.5 * min(1.0, max(entry["specular"])) ** (1 / 2.2)
    emission = entry["emission"]
    if max(emission) > 0:
        bsdf.inputs["Emission"].default_value = tuple(emission) + (1.0,)
    if entry["alpha"] < 1:
        bsdf.inputs["Alpha"].default_value = entry["alpha"]
        material.blend_method = "HASHED"
    if coloured:
        attribute = nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = "colour"
        links.new(attribute.outputs["Color"], bsdf.inputs["Base Color"])
    links.new(bsdf.outputs[0], output.inputs["Surface"])
    material.diffuse_color = diffuse
    return material


class Importer:
    def __init__(self, path, context):
        self.path = path
        self.context = context
        self.data, self.index = read_index(path)
        self.materials = {}
        self.collections = {}
        stem = os.path.splitext(os.path.basename(path))[0]
        self.collection = bpy.data.collections.new("Hirsute " + stem)
        context.scene.collection.children.link(self.collection)
        # Hirsute's y is up, Blender's z: every object hangs from an empty turned 90° about x.
        self.root = bpy.data.objects.new(stem, None)
        self.root.rotation_euler = (math.pi / 2, 0.0, 0.0)
        self.collection.objects.link(self.root)
        self.curve_objects = []
        self.mesh_objects = []

    def material(self, number, coloured=False):
        if not 0 <= number < len(self.index["materials"]):
            raise HirsuteFileError(f"material {number} is not in the file")
        key = (number, coloured)
        if key not in self.materials:
            self.materials[key] = make_material(self.index["materials"][number], coloured)
        return self.materials[key]

    def organ_collection(self, organ):
        if organ not in self.collections:
            collection = bpy.data.collections.new(organ)
            self.collection.children.link(collection)
            self.collections[organ] = collection
        return self.collections[organ]

    def place(self, obj, organ=None):
        (self.organ_collection(organ) if organ else self.collection).objects.link(obj)
        obj.parent = self.root

    def mesh(self, entry):
        data, n, t = self.data, entry["vertices"], entry["triangles"]
        mesh = bpy.data.meshes.new(entry["name"])
        mesh.vertices.add(n)
        mesh.vertices.foreach_set("co", floats(data, entry["positions"], 3 * n))
        indices = uints(data, entry["indices"], 3 * t)
        if t > 0 and max(indices) >= n:
            raise HirsuteFileError(f"mesh {entry['name']}: a triangle names a vertex past {n}")
        mesh.loops.add(3 * t)
        mesh.loops.foreach_set("vertex_index", indices)
        mesh.polygons.add(t)
        mesh.polygons.foreach_set("loop_start", array.array("i", range(0, 3 * t, 3)))
        mesh.polygons.foreach_set("loop_total", array.array("i", [3]) * t)
        mesh.polygons.foreach_set("use_smooth", array.array("b", [1]) * t)
        if entry["texcoords"] is not None:
            uv = floats(data, entry["texcoords"], 2 * n)
            per_loop = array.array("f", [0.0]) * (6 * t)
            per_loop[0::2] = array.array("f", (uv[2 * i] for i in indices))
            per_loop[1::2] = array.array("f", (uv[2 * i + 1] for i in indices))
            mesh.uv_layers.new(name="UVMap").data.foreach_set("uv", per_loop)
        coloured = entry["colours"] is not None
        if coloured:
            rgb = floats(data, entry["colours"], 3 * n)
            rgba = array.array("f", [1.0]) * (4 * n)
            for k in range(3):
                rgba[k::4] = rgb[k::3]
            mesh.color_attributes.new("colour", "FLOAT_COLOR", "POINT").data.foreach_set(
                "color", rgba)
        mesh.update()
        if entry["normals"] is not None:
            normals = floats(data, entry["normals"], 3 * n)
            mesh.use_auto_smooth = True
            mesh.normals_split_custom_set_from_vertices(
                list(zip(normals[0::3], normals[1::3], normals[2::3])))
        mesh.materials.append(self.material(entry["material"], coloured))
        obj = bpy.data.objects.new(f"{entry['organ']}: {entry['name']}", mesh)
        self.place(obj, entry["organ"])
        self.mesh_objects.append(obj)
        return obj

    def curves(self, entry):
        """A curve group as a Curves object: radius and colour at each point."""
        data, count, points = self.data, entry["curves"], entry["points"]
        record = floats(data, entry["data"], POINT_FLOATS * points)
        sizes = uints(data, entry["sizes"], count)
        if sum(sizes) != points or (count > 0 and min(sizes) < 2):
            raise HirsuteFileError(f"curves {entry['name']}: the curves' sizes do not add up to "
                                   f"their {points} points")
        mesh = bpy.data.meshes.new(entry["name"])
        mesh.vertices.add(points)
        position = array.array("f", [0.0]) * (3 * points)
        for k in range(3):
            position[k::3] = record[k::POINT_FLOATS]
        mesh.vertices.foreach_set("co", position)
        # Each curve a chain of edges from its first point to its last.
        starts = array.array("i")
        first = 0
        for size in sizes:
            starts.extend(range(first, first + size - 1))
            first += size
        edges = array.array("i", [0]) * (2 * len(starts))
        edges[0::2] = starts
        edges[1::2] = array.array("i", (s + 1 for s in starts))
        mesh.edges.add(len(starts))
        mesh.edges.foreach_set("vertices", edges)
        mesh.attributes.new("radius", "FLOAT", "POINT").data.foreach_set(
            "value", record[3::POINT_FLOATS])
        rgba = array.array("f", [1.0]) * (4 * points)
        for k in range(3):
            rgba[k::4] = record[4 + k::POINT_FLOATS]
        mesh.attributes.new("colour", "FLOAT_COLOR", "POINT").data.foreach_set("color", rgba)
        mesh.update()
        obj = bpy.data.objects.new(f"{entry['organ']}: {entry['name']}", mesh)
        self.place(obj, entry["organ"])
        modifier = obj.modifiers.new("to curves", "NODES")
        modifier.node_group = mesh_to_curves_nodes()
        view_layer = self.context.view_layer
        for selected in list(self.context.selected_objects):
            selected.select_set(False)
        view_layer.objects.active = obj
        obj.select_set(True)
        bpy.ops.object.convert(target="CURVES")
        obj = view_layer.objects.active
        obj.select_set(False)
        obj.data.materials.append(self.material(entry["material"]))
        self.curve_objects.append(obj)
        return obj

    def camera(self):
        c = self.index["camera"]
        data = bpy.data.cameras.new("camera")
        if c["projection"] == "perspective":
            data.type = "PERSP"
            data.sensor_fit = "VERTICAL"
            data.angle_y = math.radians(c["fov_y"])
        else:
            data.type = "ORTHO"
            data.sensor_fit = "AUTO"
            data.ortho_scale = max(c["width"], c["height"])
        data.clip_start = max(c["clip"][0], 1e-4)
        data.clip_end = max(c["clip"][1], data.clip_start * 2)
        obj = bpy.data.objects.new("camera", data)
        forward = Vector(c["forward"]).normalized()
        right = forward.cross(Vector(c["up"])).normalized()
        up = right.cross(forward)
        rotation = Matrix((right, up, -forward)).transposed()  # columns: the camera's x, y, z
        obj.matrix_basis = Matrix.Translation(Vector(c["location"])) @ rotation.to_4x4()
        self.place(obj)
        self.context.scene.camera = obj
        return obj

    def lights(self):
        size = max(self.index["size"], 1e-6)
        centre = Vector(self.index["centre"])
        for number, light in enumerate(self.index["lights"]):
            colour = Vector(light["colour"])
            strength = max(colour)
            if strength <= 0:
                continue
            kind = {"sun": "SUN", "point": "POINT", "spot": "SPOT"}[light["type"]]
            data = bpy.data.lights.new(f"light{number}", kind)
            data.color = tuple(colour / strength)
            obj = bpy.data.objects.new(f"light{number}", data)
            if kind == "SUN":
                data.energy = SUN_STRENGTH * strength
                # A sun shines along its -z: its z towards the light.
                obj.rotation_euler = Vector(light["towards"]).to_track_quat("Z", "Y").to_euler()
                obj.location = centre + Vector(light["towards"]) * size
            else:
                # A point light of power P lights a surface d away with P / (4π² d²) in Cycles;
                # GL's light has no fall-off: it is matched at the plant's centre.
                position = Vector(light["position"])
                distance = max((position - centre).length, 1e-3 * size)
                data.energy = SUN_STRENGTH * strength * 4 * math.pi ** 2 * distance ** 2 / math.pi
                data.shadow_soft_size = 0.0
                obj.location = position
                if kind == "SPOT":
                    data.spot_size = math.radians(2 * light["cutoff"])
                    data.spot_blend = min(1.0, light["exponent"] / 128.0)
                    obj.rotation_euler = (-Vector(light["direction"])).to_track_quat(
                        "Z", "Y").to_euler()
            self.place(obj)

    def world(self):
        """The camera sees the background; every other ray the view's ambient light."""
        scene = self.context.scene
        world = bpy.data.worlds.new("hirsute world")
        scene.world = world
        world.use_nodes = True
        nodes, links = world.node_tree.nodes, world.node_tree.links
        nodes.clear()
        output = nodes.new("ShaderNodeOutputWorld")
        seen = nodes.new("ShaderNodeBackground")
        seen.inputs["Color"].default_value = tuple(self.index["background"]) + (1.0,)
        ambient = nodes.new("ShaderNodeBackground")
        ambient.inputs["Color"].default_value = tuple(self.index["ambient"]) + (1.0,)
        path = nodes.new("ShaderNodeLightPath")
        mix = nodes.new("ShaderNodeMixShader")
        links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
        links.new(ambient.outputs[0], mix.inputs[1])
        links.new(seen.outputs[0], mix.inputs[2])
        links.new(mix.outputs[0], output.inputs["Surface"])

    def build(self):
        for entry in self.index["meshes"]:
            self.mesh(entry)
        for entry in self.index["curves"]:
            self.curves(entry)
        self.camera()
        self.lights()
        self.world()
        scene = self.context.scene
        scene.render.engine = "CYCLES"
        scene.render.resolution_x, scene.render.resolution_y = self.index["picture"]
        scene.render.resolution_percentage = 100
        # The colours are those of the preview: no film curve over them.
        scene.view_settings.view_transform = "Standard"
        return self


def mesh_to_curves_nodes():
    group = bpy.data.node_groups.get("hirsute mesh to curves")
    if group is not None:
        return group
    group = bpy.data.node_groups.new("hirsute mesh to curves", "GeometryNodeTree")
    group.inputs.new("NodeSocketGeometry", "Geometry")
    group.outputs.new("NodeSocketGeometry", "Geometry")
    source = group.nodes.new("NodeGroupInput")
    result = group.nodes.new("NodeGroupOutput")
    convert = group.nodes.new("GeometryNodeMeshToCurve")
    group.links.new(source.outputs[0], convert.inputs["Mesh"])
    group.links.new(convert.outputs[0], result.inputs[0])
    return group


def import_file(path, context=None):
    """Imports a Hirsute scene file into the current scene; returns the Importer (its objects)."""
    return Importer(path, context or bpy.context).build()


def read_point_cache_header(path):
    """(points, start frame, sample rate, samples) of a PC2 file, checked."""
    with open(path, "rb") as f:
        header = f.read(32)
    if len(header) < 32 or header[:12] != b"POINTCACHE2\0":
        raise HirsuteFileError("not a PC2 point cache (no POINTCACHE2 at its start)")
    version, points, start, rate, samples = struct.unpack("<iiffi", header[12:])
    if version != 1 or points < 0 or samples < 1 or rate <= 0:
        raise HirsuteFileError("a PC2 header this add-on does not read")
    if os.path.getsize(path) != 32 + 12 * points * samples:
        raise HirsuteFileError(f"{samples} samples of {points} points announced, "
                               "and the file is not that long")
    return points, start, rate, samples


def import_point_cache(path, context=None):
    """A simulation of `hirsute simulate --pc2 CACHE.pc2` in one step: the base mesh beside the
    cache (CACHE.obj) imported by Blender's OBJ importer, the cache played on it by a Mesh Cache
    modifier, frame 1 its first sample, and the scene's frames its samples. Returns the object."""
    context = context or bpy.context
    points, start, rate, samples = read_point_cache_header(path)
    base = os.path.splitext(path)[0] + ".obj"
    if not os.path.isfile(base):
        raise HirsuteFileError(f"its base mesh {base} is not there")
    before = set(bpy.data.objects)
    bpy.ops.wm.obj_import(filepath=base)
    meshes = [o for o in bpy.data.objects if o not in before and o.type == "MESH"]
    if len(meshes) != 1 or len(meshes[0].data.vertices) != points:
        raise HirsuteFileError(f"{base} is not the base mesh of the cache ({points} points)")
    obj = meshes[0]
    modifier = obj.modifiers.new("hirsute point cache", "MESH_CACHE")
    modifier.cache_format = "PC2"
    modifier.filepath = os.path.abspath(path)
    # Blender's frame F shows sample F − frame_start (the header's start frame is for other
    # programs): sample 0 is Hirsute's frame 1. The importer keeps the file's coordinates in the
    # mesh and turns y up into z up by the object's rotation, which turns the cache's points
    # alike, so the modifier's axes stay as they are.
    modifier.frame_start = start
    modifier.frame_scale = 1.0 / rate
    context.scene.frame_start = int(start)
    context.scene.frame_end = int(start + (samples - 1) * rate)
    return obj


# The add-on: File > Import > Hirsute scene.
try:
    from bpy.props import StringProperty
    from bpy_extras.io_utils import ImportHelper

    class ImportHirsute(bpy.types.Operator, ImportHelper):
        """Import a plant exported by `hirsute export --blender`"""
        bl_idname = "import_scene.hirsute"
        bl_label = "Import Hirsute scene"
        bl_options = {"REGISTER", "UNDO"}
        filename_ext = ".hirsute"
        filter_glob: StringProperty(default="*.hirsute", options={"HIDDEN"})

        def execute(self, context):
            try:
                import_file(self.filepath, context)
            except (HirsuteFileError, OSError, ValueError, KeyError, TypeError) as error:
                self.report({"ERROR"}, f"{self.filepath}: {error}")
                return {"CANCELLED"}
            return {"FINISHED"}

    def menu_entry(self, context):
        self.layout.operator(ImportHirsute.bl_idname, text="Hirsute scene (.hirsute)")

    def register():
        bpy.utils.register_class(ImportHirsute)
        bpy.types.TOPBAR_MT_file_import.append(menu_entry)

    def unregister():
        bpy.types.TOPBAR_MT_file_import.remove(menu_entry)
        bpy.utils.unregister_class(ImportHirsute)
except ImportError:  # pragma: no cover - bpy_extras is part of every Blender
    pass


def main(argv):
    import argparse
    parser = argparse.ArgumentParser(
        prog="blender -b --python hirsute_import.py --",
        description="Import a Hirsute scene file, then save and/or render it.")
    parser.add_argument("file", help="the file of `hirsute export --blender FILE`, or a point "
                                     "cache of `hirsute simulate --pc2 FILE.pc2` (with its "
                                     "base mesh FILE.obj beside it)")
    parser.add_argument("--save", metavar="OUT.blend", help="save the scene as a .blend file")
    parser.add_argument("--render", metavar="OUT.png", help="render the camera's view in Cycles")
    parser.add_argument("--samples", type=int, default=64, help="Cycles samples a pixel (64)")
    parser.add_argument("--seed", type=int, default=0,
                        help="Cycles' seed of the samples (0); two seeds, two pictures whose "
                             "difference is the noise (scripts/image-noise.py)")
    parser.add_argument("--size", metavar="WxH",
                        help="the picture's size in pixels (default: the exported --size)")
    options = parser.parse_args(argv)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    try:
        if options.file.endswith(".pc2"):
            played = import_point_cache(options.file)
            print(f"hirsute_import: {len(played.data.vertices)} points played over frames "
                  f"{bpy.context.scene.frame_start} to {bpy.context.scene.frame_end}")
        else:
            importer = import_file(options.file)
            print(f"hirsute_import: {len(importer.mesh_objects)} meshes, "
                  f"{sum(len(o.data.curves) for o in importer.curve_objects)} curves in "
                  f"{len(importer.curve_objects)} objects")
    except (HirsuteFileError, OSError, ValueError, KeyError, TypeError) as error:
        print(f"hirsute_import: error: {options.file}: {error}", file=sys.stderr)
        return 2
    scene = bpy.context.scene
    if options.size:
        try:
            width, height = (int(v) for v in options.size.lower().split("x"))
        except ValueError:
            print(f"hirsute_import: error: --size {options.size}: WIDTHxHEIGHT expected",
                  file=sys.stderr)
            return 2
        scene.render.resolution_x, scene.render.resolution_y = width, height
    if options.save:
        bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(options.save))
    if options.render:
        scene.cycles.samples = max(1, options.samples)
        scene.cycles.seed = options.seed
        scene.cycles.device = "CPU"
        # Debian's Blender is built without OpenImageDenoise: the samples alone.
        scene.cycles.use_denoising = False
        scene.render.image_settings.file_format = "PNG"
        scene.render.filepath = os.path.abspath(options.render)
        bpy.ops.render.render(write_still=True)
    return 0


if __name__ == "__main__":
    # Run as `blender -b --python hirsute_import.py -- FILE …`: the arguments after `--`.
    if "--" in sys.argv:
        sys.exit(main(sys.argv[sys.argv.index("--") + 1:]))
    register()
