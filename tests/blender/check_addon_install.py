# Run by blender_import_test.sh inside Blender (blender -b --python check_addon_install.py --
# ADDON FILE), with BLENDER_USER_SCRIPTS pointing at a scratch folder: the add-on installs and
# enables as Blender's preferences install it, and its File > Import operator builds the scene.
import sys

import addon_utils
import bpy

addon, scene_file = sys.argv[sys.argv.index("--") + 1:]
bpy.ops.preferences.addon_install(filepath=addon)
bpy.ops.preferences.addon_enable(module="hirsute_import")
enabled = addon_utils.check("hirsute_import")[1]
print(("ok: " if enabled else "FAILED: ") + "the add-on installs and is enabled")
# The start-up scene's objects away (factory settings would unload the add-on too).
for obj in list(bpy.data.objects):
    bpy.data.objects.remove(obj)
result = bpy.ops.import_scene.hirsute(filepath=scene_file)
kinds = sorted({o.type for o in bpy.data.objects})
imported = result == {"FINISHED"} and {"CAMERA", "CURVES", "LIGHT", "MESH"} <= set(kinds)
print(("ok: " if imported else "FAILED: ") + f"File > Import > Hirsute scene: {result}, {kinds}")
if not (enabled and imported):
    sys.exit(1)
