# Renders docs/images/blender-coat-cache.png, a frame of a simulated coat played by Blender from
# its point cache (docs/export.md, "Point caches"). Run inside Blender:
#   blender -b --python scripts/point-cache-doc-image.py -- COAT.pc2 FRAME OUT.png
# The add-on blender/hirsute_import.py sets the cache up (its base mesh and a Mesh Cache
# modifier); a cache has no camera or lights, so this script frames the played mesh as it is at
# the first and last frames (every frame alike, so that the pictures of two frames compare),
# from the front (Hirsute's +z, cpfg's default viewpoint) with a sun over the camera's shoulder
# and a grey sky, and renders it in Cycles.
import math
import os
import sys

import bpy
from mathutils import Vector

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "blender"))
import hirsute_import  # noqa: E402

cache, frame, out = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
played = hirsute_import.import_point_cache(cache)
scene = bpy.context.scene
corners = []
for shown in (scene.frame_start, scene.frame_end):
    scene.frame_set(shown)
    evaluated = played.evaluated_get(bpy.context.evaluated_depsgraph_get())
    corners += [played.matrix_world @ Vector(c) for c in evaluated.bound_box]
low = Vector(min(c[i] for c in corners) for i in range(3))
high = Vector(max(c[i] for c in corners) for i in range(3))
centre, extent = (low + high) / 2, high - low
scene.frame_set(int(frame))

# Hirsute's +z is Blender's -y: the camera stands there and looks along +y.
camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
camera.data.type = "ORTHO"
scene.render.resolution_x, scene.render.resolution_y = 480, 360
camera.data.ortho_scale = 1.15 * max(extent.x, extent.z * 480 / 360)
camera.location = centre - Vector((0, extent.length * 2, 0))
camera.rotation_euler = (math.pi / 2, 0, 0)
camera.data.clip_end = extent.length * 5
scene.collection.objects.link(camera)
scene.camera = camera
sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
sun.data.energy = 3.0
sun.rotation_euler = Vector((-0.4, -1.0, 0.6)).to_track_quat("Z", "Y").to_euler()
scene.collection.objects.link(sun)
world = bpy.data.worlds.new("sky")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.3, 0.32, 0.35, 1)
scene.world = world
scene.render.engine = "CYCLES"
scene.cycles.samples = 32
scene.cycles.device = "CPU"
scene.cycles.use_denoising = False
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = os.path.abspath(out)
bpy.ops.render.render(write_still=True)
print(f"frame {frame} of {scene.frame_end}: {len(played.data.vertices)} points → {out}")
