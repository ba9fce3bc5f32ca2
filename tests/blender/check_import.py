# Run by blender_import_test.sh inside Blender (blender -b --python check_import.py -- ADDON
# FILE HAIRS RENDER.png): imports FILE with the add-on and checks the scene it builds against
# Hirsute's own figures. The hair curves are as many as the hairs' table's rows; every object
# lies in the camera's view and the plant fills it as the exported picture does; and the render
# of the import with its hairs (RENDER.png, made by the add-on's command line) is brighter than
# the same render without them where the white hairs stand.
import importlib.util
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

addon_path, scene_file, hairs, render_path = sys.argv[sys.argv.index("--") + 1:]
spec = importlib.util.spec_from_file_location("hirsute_import", addon_path)
addon = importlib.util.module_from_spec(spec)
spec.loader.exec_module(addon)

failures = []


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


bpy.ops.wm.read_factory_settings(use_empty=True)
imported = addon.import_file(scene_file)
scene = bpy.context.scene
bpy.context.view_layer.update()

hair_objects = [o for o in imported.curve_objects if o.users_collection[0].name.startswith("hairs")]
curves = sum(len(o.data.curves) for o in hair_objects)
check(all(o.type == "CURVES" for o in imported.curve_objects),
      "the curve groups are Curves objects")
check(curves == int(hairs), f"{curves} hair curves in Blender, {hairs} hairs in the table")
radii = [a.value for o in hair_objects for a in o.data.attributes["radius"].data[:100]]
check(radii and min(radii) > 0, "the hair curves have a radius at each point")
check(all(m.node_tree.nodes.get("Principled Hair BSDF") for o in hair_objects
          for m in o.data.materials), "the hairs are shaded by the principled hair BSDF")

# The camera: every mesh's bounding box in the view, and the plant as wide as the picture's
# fitted window (the exported camera frames the plant's box).
camera = scene.camera
low, high = Vector((1e9, 1e9)), Vector((-1e9, -1e9))
for obj in imported.mesh_objects + imported.curve_objects:
    for corner in obj.bound_box:
        p = world_to_camera_view(scene, camera, obj.matrix_world @ Vector(corner))
        low = Vector((min(low.x, p.x), min(low.y, p.y)))
        high = Vector((max(high.x, p.x), max(high.y, p.y)))
        check_z = p.z > 0
        if not check_z:
            failures.append(f"{obj.name} behind the camera")
check(low.x >= -0.01 and low.y >= -0.01 and high.x <= 1.01 and high.y <= 1.01,
      f"the plant lies in the camera's view: {tuple(low)} to {tuple(high)}")
check(max(high.x - low.x, high.y - low.y) > 0.5, "the plant fills the view")

# Hair pixels: the same render without the hairs.
with_hairs = bpy.data.images.load(render_path)
width, height = with_hairs.size
check((width, height) == (96, 72), f"the render is {width}x{height}")
for obj in hair_objects:
    obj.hide_render = True
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.cycles.samples = 8
scene.cycles.use_denoising = False
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = render_path.replace(".png", "-without-hairs.png")
bpy.ops.render.render(write_still=True)
without = bpy.data.images.load(scene.render.filepath)
a, b = list(with_hairs.pixels), list(without.pixels)
brighter = darker = 0
for i in range(0, len(a), 4):
    difference = sum(a[i:i + 3]) / 3 - sum(b[i:i + 3]) / 3
    brighter += difference > 0.1
    darker += difference < -0.1
pixels = width * height
check(brighter > 0.01 * pixels and brighter > 3 * darker,
      f"hair pixels: {brighter} pixels brighter with the hairs, {darker} darker, of {pixels}")

if failures:
    print(f"{len(failures)} checks failed", file=sys.stderr)
    sys.exit(1)
