# Run by obj_import_test.sh inside Blender (blender -b --python check_obj_import.py -- FILE.obj
# SEGMENTS): imports the OBJ with each of Blender's importers, the default (C++) one and the
# legacy Python one, and checks that each keeps every segment of the `l` elements as an edge of
# its own (loose edges: the faces' edges aside), SEGMENTS of them.
import sys

import bpy

obj_file, segments = sys.argv[sys.argv.index("--") + 1:]
failures = []
for name, run in (("default", lambda: bpy.ops.wm.obj_import(filepath=obj_file)),
                  ("legacy", lambda: bpy.ops.import_scene.obj(filepath=obj_file))):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    run()
    loose = sum(sum(1 for e in o.data.edges if e.is_loose)
                for o in bpy.data.objects if o.type == "MESH")
    ok = loose == int(segments)
    print(("ok: " if ok else "FAILED: ") + f"the {name} importer: {loose} loose edges, "
          f"{segments} segments in the file")
    if not ok:
        failures.append(name)
if failures:
    sys.exit(1)
