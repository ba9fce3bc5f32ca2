# Run by point_cache_test.sh inside Blender (blender -b --python check_point_cache.py -- ADDON
# CACHE.pc2 FRAME1.obj FRAME2.obj …): the add-on imports the cache's base mesh with Blender's
# default OBJ importer and plays the cache on it with the Mesh Cache modifier; this compares the
# deformed mesh at each frame with that frame's own OBJ, vertex by vertex (in the object's own
# coordinates), within the precision the OBJ is printed with. The frames must differ from the
# first, or the comparison would prove nothing.
import importlib.util
import struct
import sys

import bpy
from mathutils import Vector

addon_path, cache, *frames = sys.argv[sys.argv.index("--") + 1:]
spec = importlib.util.spec_from_file_location("hirsute_import", addon_path)
addon = importlib.util.module_from_spec(spec)
spec.loader.exec_module(addon)
failures = []


def check(condition, message):
    print(("ok: " if condition else "FAILED: ") + message)
    if not condition:
        failures.append(message)


def obj_vertices(path):
    """The `v` lines of an OBJ."""
    points = []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                x, y, z = (float(w) for w in line.split()[1:4])
                points.append(Vector((x, y, z)))
    return points


with open(cache, "rb") as f:
    header = f.read(32)
check(header[:12] == b"POINTCACHE2\0", "the cache starts with POINTCACHE2")
version, points, start, rate, samples = struct.unpack("<iiffi", header[12:])
check((version, start, rate, samples) == (1, 1.0, 1.0, len(frames)),
      f"version {version}, start frame {start}, sample rate {rate}, {samples} samples")

bpy.ops.wm.read_factory_settings(use_empty=True)
obj = addon.import_point_cache(cache)
check(len(obj.data.vertices) == points, f"{len(obj.data.vertices)} vertices, {points} points")
check((bpy.context.scene.frame_start, bpy.context.scene.frame_end) == (1, len(frames)),
      "the scene's frames are the cache's")

first = obj_vertices(frames[0])
size = max((max(p[k] for p in first) - min(p[k] for p in first)) for k in range(3))
tolerance = 1e-5 * size
for number, path in enumerate(frames, start=1):
    bpy.context.scene.frame_set(number)
    evaluated = obj.evaluated_get(bpy.context.evaluated_depsgraph_get())
    played = [v.co.copy() for v in evaluated.data.vertices]
    expected = obj_vertices(path)
    check(len(played) == len(expected), f"frame {number}: {len(played)} vertices")
    error = max((a - b).length for a, b in zip(played, expected))
    moved = max((a - b).length for a, b in zip(expected, first))
    check(error <= tolerance,
          f"frame {number}: the cache within {error:.3g} of the frame's OBJ "
          f"(at most {tolerance:.3g})")
    if number > 1:
        check(moved > 100 * tolerance, f"frame {number}: the coat moved by up to {moved:.3g}")
if failures:
    sys.exit(1)
