# Run by bench-cycles.sh inside Blender (blender -b --python bench-cycles-scene.py -- SCENE
# SAMPLES OUT.png SEED LIGHT SKY): imports the scene file with the add-on
# blender/hirsute_import.py, then lights it as `render --trace` lights the plant instead of with
# the view's GL lights, and renders it in Cycles on the CPU.
#   LIGHT: "x,y,z degrees r,g,b", the view's `trace light:` (towards the light, its angular
#          size, its irradiance); SKY: "r,g,b", `trace sky:`, the radiance of the hemisphere above
#          (+y, Blender's +z): nothing below. Camera rays still see the background.
# Cycles' sun of strength E lights a white diffuse surface facing it to E / π, as the tracer's
# light of irradiance E does (docs/trace.md); its world of colour L is a radiance L.
import math
import os
import sys

import bpy
from mathutils import Vector

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "blender"))
import hirsute_import  # noqa: E402

scene_file, samples, out, seed, light, sky = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.wm.read_factory_settings(use_empty=True)
importer = hirsute_import.import_file(scene_file)
scene = bpy.context.scene
for obj in [o for o in scene.objects if o.type == "LIGHT"]:
    bpy.data.objects.remove(obj)


def triple(text):
    return Vector(float(v) for v in text.split(","))


def upright(v):  # Hirsute's y up to Blender's z up, as the add-on turns the plant
    return Vector((v.x, -v.z, v.y))


towards, degrees, irradiance = light.split()
irradiance = triple(irradiance)
sun = bpy.data.lights.new("trace light", "SUN")
sun.energy = max(irradiance)
sun.color = tuple(irradiance / max(irradiance))
sun.angle = math.radians(float(degrees))
obj = bpy.data.objects.new("trace light", sun)
obj.rotation_euler = upright(triple(towards)).normalized().to_track_quat("Z", "Y").to_euler()
scene.collection.objects.link(obj)

# The world: the background to camera rays, the sky above to the others, black below.
nodes, links = scene.world.node_tree.nodes, scene.world.node_tree.links
ambient = [n for n in nodes if n.type == "BACKGROUND"][1]
direction = nodes.new("ShaderNodeTexCoord")
split = nodes.new("ShaderNodeSeparateXYZ")
above = nodes.new("ShaderNodeMath")
above.operation = "GREATER_THAN"
above.inputs[1].default_value = 0.0
colour = nodes.new("ShaderNodeMixRGB")
colour.inputs["Color1"].default_value = (0, 0, 0, 1)
colour.inputs["Color2"].default_value = tuple(triple(sky)) + (1.0,)
links.new(direction.outputs["Generated"], split.inputs[0])
links.new(split.outputs["Z"], above.inputs[0])
links.new(above.outputs[0], colour.inputs["Fac"])
links.new(colour.outputs[0], ambient.inputs["Color"])
ambient.inputs["Strength"].default_value = 1.0

scene.cycles.samples = max(1, int(samples))
# Every pixel takes the samples, as the tracer's do at --noise 0: Cycles' adaptive sampling
# (on by default, stopping at its noise threshold of 0.01) would make SAMPLES a ceiling.
scene.cycles.use_adaptive_sampling = False
scene.cycles.seed = int(seed)
scene.cycles.device = "CPU"
scene.cycles.use_denoising = False
scene.render.image_settings.file_format = "PNG"
scene.render.filepath = os.path.abspath(out)
bpy.ops.render.render(write_still=True)
