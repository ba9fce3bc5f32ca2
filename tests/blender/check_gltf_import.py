# Run by gltf_import_test.sh inside Blender (blender -b --python check_gltf_import.py -- FILE
# MESHES TRIANGLES): imports the glTF (.gltf or .glb) with Blender's own importer and checks that
# it finds MESHES mesh objects of TRIANGLES triangles in all, their materials' colours, and one
# camera that sees them: the centre of their bounds in its picture.
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

# Debian 12's Blender 3.4 imports glTF with numpy.bool, which numpy 1.24 (Debian 12's) removed:
# the alias it stood for (docs/export.md, "glTF").
import numpy

if not hasattr(numpy, "bool"):
    numpy.bool = bool

gltf_file, meshes, triangles = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=gltf_file)
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


mesh_objects = [o for o in bpy.data.objects if o.type == "MESH"]
found = sum(len(p.vertices) - 2 for o in mesh_objects for p in o.data.polygons)
check(len(mesh_objects) == int(meshes), f"{len(mesh_objects)} meshes, {meshes} written")
check(found == int(triangles), f"{found} triangles, {triangles} of area written")
colours = {tuple(round(c, 3) for c in
                 m.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value)
           for o in mesh_objects for m in o.data.materials}
check(len(colours) == len(mesh_objects) and all(0 < max(c[:3]) <= 1 for c in colours),
      f"the materials' base colours {sorted(colours)}")
cameras = [o for o in bpy.data.objects if o.type == "CAMERA"]
check(len(cameras) == 1, f"{len(cameras)} cameras")
if cameras:
    corners = [o.matrix_world @ Vector(c) for o in mesh_objects for c in o.bound_box]
    centre = sum(corners, Vector()) / len(corners)
    seen = world_to_camera_view(bpy.context.scene, cameras[0], centre)
    check(0 < seen.x < 1 and 0 < seen.y < 1 and seen.z > 0,
          f"the meshes' centre seen by the camera at {tuple(round(v, 3) for v in seen)}")
if failures:
    sys.exit(1)
