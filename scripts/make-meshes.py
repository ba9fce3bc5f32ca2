#!/usr/bin/env python3
"""Builds the mesh files of models/mesh-leaf, mesh-body and mesh-bird (docs/meshes.md).

Each mesh is made here from formulas, so that the models carry no file of unknown origin:

  mesh-leaf/leaf.ply   a leaf blade as a scanner would give it: an ASCII PLY of positions and
                       triangles only (no normals, no texture coordinates), the blade an
                       elliptic outline bent down along its midrib and cupped across it;
  mesh-body/body.obj   an animal-like body: a torso, a neck and a head blended as one smooth
                       closed surface of revolution about a bent spine, with normals and a
                       texture atlas cut along its belly (a UV seam) and at the two poles;
  mesh-bird/bird.obj   a bird's body made the same way: a plump convex body tapering from
                       the breast to the head, its atlas's v running from the tail to the beak; open at
                       the tail, where a bird's tail feathers would grow;
  mesh-bird/nod.NNNN.obj  the same bird, coarser, nodding over 12 frames: a mesh sequence of
                       the same vertices and triangles in every frame, for `hirsute simulate`;
  tests/fixtures/interpreter/bending-strip.gltf  a strip skinned to two bones, the upper one
                       turning 90 degrees about x over a second: an animated file;
  tests/fixtures/hairs/torus.ply, bumpy-sphere.ply  closed meshes of positions and triangles
                       only (no texture coordinates): a torus of radii 3 and 1, and a sphere of
                       radius 2 with bumps, for the fur's atlas of charts.

Run from the repository root: python3 scripts/make-meshes.py
"""
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NOD_FRAMES = 12


def leaf(rows=40, columns=16):
    """The blade along +y (the turtle's heading), its width along x, its front facing +z."""
    length, width = 6.0, 2.4
    points, triangles = [], []
    for i in range(rows + 1):
        t = i / rows
        half = 0.5 * width * math.sin(math.pi * t) ** 0.8 * (1.0 - 0.25 * t)
        for j in range(columns + 1):
            s = 2.0 * j / columns - 1.0
            x = s * half
            y = t * length
            # bent down towards the tip, cupped up towards the edges
            z = -0.35 * length * t * t + 0.35 * (s * s) * half
            points.append((x, y, z))
    for i in range(rows):
        for j in range(columns):
            a = i * (columns + 1) + j
            b, c, d = a + 1, a + columns + 1, a + columns + 2
            triangles.append((a, b, d))
            triangles.append((a, d, c))
    # The base and the tip have no width: their columns are one point, so those triangles have
    # no area. A scanner's mesh has none there: they are left out here.
    kept = []
    for a, b, c in triangles:
        pa, pb, pc = points[a], points[b], points[c]
        u = [pb[k] - pa[k] for k in range(3)]
        v = [pc[k] - pa[k] for k in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        if math.sqrt(sum(x * x for x in n)) > 1e-9:
            kept.append((a, b, c))
    return points, kept


def write_ply(path, points, triangles, comment):
    with open(path, "w") as out:
        out.write("ply\nformat ascii 1.0\n")
        out.write("comment %s\n" % comment)
        out.write("element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                  % len(points))
        out.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                  % len(triangles))
        for p in points:
            out.write("%.6f %.6f %.6f\n" % p)
        for t in triangles:
            out.write("3 %d %d %d\n" % t)


def bird_radius(t):
    """A plump bird: a convex body tapering from the breast to the head, with no neck, so that
    a coat lying towards the tail rides over it everywhere."""
    return 1.15 * math.sin(math.pi * t) ** 0.5 * (1.0 - 0.45 * t)


def animal_radius(t):
    """An animal: a long torso, a neck and a head."""
    torso = 1.05 * math.sin(math.pi * min(t / 0.7, 1.0)) ** 0.6 if t < 0.7 else 0.0
    head = 0.55 * math.sin(math.pi * max(0.0, (t - 0.66) / 0.34)) ** 0.7 if t > 0.66 else 0.0
    neck = 0.5 if 0.55 < t < 0.8 else 0.0
    return max(torso, head, neck * math.sin(math.pi * (t - 0.55) / 0.25), 0.0)


def body(rings=48, sides=32, radius=animal_radius, length=5.0, rise=1.4, open_tail=False):
    """A body along +y: radius r(t) about a spine that bends forward into the neck and head.

    t runs from the tail (0) to the nose (1); the angle a around the spine from the back (0)
    over the side to the belly (pi) and back. The texture atlas: u = (a - pi) / 2pi, v = t, cut
    along the belly line a = pi (its vertices doubled) and pinched at the two poles.
    """
    def spine(t):
        # straight along +y for the torso, rising (+z is up) into the neck and head
        y = length * t
        z = rise * max(0.0, t - 0.62) ** 2 / 0.38 ** 2
        return (0.0, y, z)

    def frame(t):
        e = 1e-4
        a, b = spine(max(0.0, t - e)), spine(min(1.0, t + e))
        d = [b[k] - a[k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in d))
        h = [x / n for x in d]
        # "up" is +z made perpendicular to the heading, "side" completes the frame
        up = [0.0, 0.0, 1.0]
        dot = sum(up[k] * h[k] for k in range(3))
        up = [up[k] - dot * h[k] for k in range(3)]
        n = math.sqrt(sum(x * x for x in up))
        up = [x / n for x in up]
        side = [h[1] * up[2] - h[2] * up[1], h[2] * up[0] - h[0] * up[2], h[0] * up[1] - h[1] * up[0]]
        return h, up, side

    def point(t, a):
        c = spine(t)
        h, up, side = frame(t)
        r = radius(t)
        # the torso a little wider than high
        sx, sz = 1.1 * math.sin(a), math.cos(a)
        return tuple(c[k] + r * (sx * side[k] + sz * up[k]) for k in range(3))

    positions, uvs, faces = [], [], []
    # ring vertices: rings-1 inner rings; the poles are single points
    index = {}
    for i in range(1, rings):
        t = i / rings
        for j in range(sides + 1):
            a = math.pi + 2.0 * math.pi * j / sides  # from the belly, over a side, the back
            index[(i, j)] = len(positions)
            positions.append(point(t, a))
            uvs.append((j / sides, t))
    tail, nose = len(positions), len(positions) + 1
    positions.append(point(0.0, 0.0))
    positions.append(point(1.0, 0.0))
    uvs.append((0.5, 0.0))
    uvs.append((0.5, 1.0))
    for i in range(1, rings - 1):
        for j in range(sides):
            a, b = index[(i, j)], index[(i, j + 1)]
            c, d = index[(i + 1, j)], index[(i + 1, j + 1)]
            faces.append((a, d, c))
            faces.append((a, b, d))
    for j in range(sides):
        if not open_tail:
            faces.append((tail, index[(1, j + 1)], index[(1, j)]))
        faces.append((nose, index[(rings - 1, j)], index[(rings - 1, j + 1)]))
    if open_tail:
        # the tail end is left open (where a bird's tail feathers would be): no pole there, so
        # the coat's flow does not converge into a point
        first = 4
        faces = [f for f in faces if all(k == nose or k >= index[(first, 0)] for k in f)]
        used = sorted({k for f in faces for k in f})
        renumber = {k: n for n, k in enumerate(used)}
        positions = [positions[k] for k in used]
        uvs = [uvs[k] for k in used]
        faces = [tuple(renumber[k] for k in f) for f in faces]

    # Vertex normals: area-weighted face normals, summed over the vertices that are one point
    # (the doubled seam), so that the seam does not show in the shading.
    def key(p):
        return tuple(round(x, 6) for x in p)
    sums = {}
    for f in faces:
        p = [positions[k] for k in f]
        u = [p[1][k] - p[0][k] for k in range(3)]
        v = [p[2][k] - p[0][k] for k in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        for k in f:
            s = sums.setdefault(key(positions[k]), [0.0, 0.0, 0.0])
            for m in range(3):
                s[m] += n[m]
    normals = []
    for p in positions:
        s = sums[key(p)]
        n = math.sqrt(sum(x * x for x in s)) or 1.0
        normals.append(tuple(x / n for x in s))
    return positions, normals, uvs, faces


def write_obj(path, positions, normals, uvs, faces, comment):
    with open(path, "w") as out:
        out.write("# %s\n" % comment)
        for p in positions:
            out.write("v %.5f %.5f %.5f\n" % p)
        for t in uvs:
            out.write("vt %.5f %.5f\n" % t)
        for n in normals:
            out.write("vn %.4f %.4f %.4f\n" % n)
        for f in faces:
            out.write("f %s\n" % " ".join("%d/%d/%d" % (k + 1, k + 1, k + 1) for k in f))



def skinned_strip():
    """A glTF 2.0 file of a strip skinned to two bones, the second bending 90 degrees about x
    over one second: a moving body Assimp reads as an animated file."""
    import base64
    import json
    import struct
    rows, height = 8, 2.0
    positions, normals, uvs, joints, weights, indices = [], [], [], [], [], []
    for i in range(rows + 1):
        y = height * i / rows
        w = min(1.0, max(0.0, (y - 0.5) / 1.0))  # the upper bone's share, 0 below 0.5, 1 above 1.5
        for x in (-0.25, 0.25):
            positions.append((x, y, 0.0))
            normals.append((0.0, 0.0, 1.0))
            uvs.append((x + 0.25, y / height))
            joints.append((0, 1, 0, 0))
            weights.append((1.0 - w, w, 0.0, 0.0))
    for i in range(rows):
        a, b, c, d = 2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3
        indices += [a, b, d, a, d, c]
    times = [0.0, 0.5, 1.0]
    half = [math.radians(a) / 2 for a in (0.0, 45.0, 90.0)]
    rotations = [(math.sin(h), 0.0, 0.0, math.cos(h)) for h in half]
    # inverse bind matrices (column-major): bone 0 at the origin, bone 1 at y = 1
    inverse_bind = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
                    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1]
    parts = []
    views = []

    def add(data, target=None):
        offset = sum(len(p) for p in parts)
        while len(data) % 4:
            data += b"\0"
        parts.append(data)
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(data)}
        if target:
            view["target"] = target
        views.append(view)
        return len(views) - 1
    flat = lambda rows: [v for row in rows for v in row]
    v_pos = add(struct.pack("<%df" % (3 * len(positions)), *flat(positions)), 34962)
    v_nor = add(struct.pack("<%df" % (3 * len(normals)), *flat(normals)), 34962)
    v_uv = add(struct.pack("<%df" % (2 * len(uvs)), *flat(uvs)), 34962)
    v_joi = add(struct.pack("<%dH" % (4 * len(joints)), *flat(joints)), 34962)
    v_wei = add(struct.pack("<%df" % (4 * len(weights)), *flat(weights)), 34962)
    v_ind = add(struct.pack("<%dH" % len(indices), *indices), 34963)
    v_ibm = add(struct.pack("<32f", *inverse_bind))
    v_tim = add(struct.pack("<3f", *times))
    v_rot = add(struct.pack("<12f", *flat(rotations)))
    n = len(positions)
    accessors = [
        {"bufferView": v_pos, "componentType": 5126, "count": n, "type": "VEC3",
         "min": [-0.25, 0.0, 0.0], "max": [0.25, height, 0.0]},
        {"bufferView": v_nor, "componentType": 5126, "count": n, "type": "VEC3"},
        {"bufferView": v_uv, "componentType": 5126, "count": n, "type": "VEC2"},
        {"bufferView": v_joi, "componentType": 5123, "count": n, "type": "VEC4"},
        {"bufferView": v_wei, "componentType": 5126, "count": n, "type": "VEC4"},
        {"bufferView": v_ind, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        {"bufferView": v_ibm, "componentType": 5126, "count": 2, "type": "MAT4"},
        {"bufferView": v_tim, "componentType": 5126, "count": 3, "type": "SCALAR",
         "min": [0.0], "max": [1.0]},
        {"bufferView": v_rot, "componentType": 5126, "count": 3, "type": "VEC4"},
    ]
    data = b"".join(parts)
    gltf = {
        "asset": {"version": "2.0", "generator": "scripts/make-meshes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"name": "strip", "mesh": 0, "skin": 0},
            {"name": "lower", "children": [2]},
            {"name": "upper", "translation": [0.0, 1.0, 0.0]},
        ],
        "meshes": [{"name": "strip", "primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2, "JOINTS_0": 3,
                           "WEIGHTS_0": 4},
            "indices": 5}]}],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": 6}],
        "animations": [{"name": "bend", "samplers": [{"input": 7, "output": 8,
                                                      "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0,
                                      "target": {"node": 2, "path": "rotation"}}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64,"
                            + base64.b64encode(data).decode("ascii")}],
        "bufferViews": views,
        "accessors": accessors,
    }
    return json.dumps(gltf, indent=1)

def torus(ring=48, sides=20, big=3.0, small=1.0):
    """A closed torus about z: positions and counter-clockwise triangles, outward."""
    points, triangles = [], []
    for i in range(ring):
        a = 2.0 * math.pi * i / ring
        for j in range(sides):
            b = 2.0 * math.pi * j / sides
            r = big + small * math.cos(b)
            points.append((r * math.cos(a), r * math.sin(a), small * math.sin(b)))
    for i in range(ring):
        for j in range(sides):
            p = i * sides + j
            q = ((i + 1) % ring) * sides + j
            p1 = i * sides + (j + 1) % sides
            q1 = ((i + 1) % ring) * sides + (j + 1) % sides
            triangles += [(p, q, q1), (p, q1, p1)]
    return points, triangles


def bumpy_sphere(level=4, radius=2.0, bump=0.12):
    """An icosahedron subdivided `level` times onto a sphere whose radius rises and falls in
    bumps: positions and counter-clockwise triangles, outward."""
    t = (1.0 + math.sqrt(5.0)) / 2.0
    points = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
              (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    points = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in points]
    triangles = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9),
                 (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2),
                 (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
                 (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        middle = {}

        def half(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = [(x + y) / 2.0 for x, y in zip(points[a], points[b])]
                n = math.sqrt(sum(x * x for x in m))
                points.append(tuple(x / n for x in m))
                middle[key] = len(points) - 1
            return middle[key]

        finer = []
        for a, b, c in triangles:
            ab, bc, ca = half(a, b), half(b, c), half(c, a)
            finer += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        triangles = finer
    bumpy = []
    for x, y, z in points:
        r = radius * (1.0 + bump * math.sin(5.0 * x) * math.sin(4.0 * y + 1.0) * math.cos(3.0 * z))
        bumpy.append((r * x, r * y, r * z))
    return bumpy, triangles


def main():
    points, triangles = leaf()
    write_ply(os.path.join(ROOT, "models/mesh-leaf/leaf.ply"), points, triangles,
              "leaf blade made by scripts/make-meshes.py")
    positions, normals, uvs, faces = body()
    write_obj(os.path.join(ROOT, "models/mesh-body/body.obj"), positions, normals, uvs, faces,
              "animal-like body made by scripts/make-meshes.py")
    bird = body(radius=bird_radius, length=4.0, rise=0.0, open_tail=True)
    write_obj(os.path.join(ROOT, "models/mesh-bird/bird.obj"), *bird,
              "bird body made by scripts/make-meshes.py")
    # The bird nodding: 12 frames in which its front half rises and falls once, the same
    # vertices and triangles in every frame (as an animation exported frame by frame).
    for k in range(1, NOD_FRAMES + 1):
        rise = 0.9 * math.sin(2.0 * math.pi * (k - 1) / NOD_FRAMES)
        frame = body(rings=32, sides=24, radius=bird_radius, length=4.0, rise=rise,
                     open_tail=True)
        write_obj(os.path.join(ROOT, "models/mesh-bird/nod.%04d.obj" % k), *frame,
                  "frame %d of the nodding bird, made by scripts/make-meshes.py" % k)
    with open(os.path.join(ROOT, "tests/fixtures/interpreter/bending-strip.gltf"), "w") as out:
        out.write(skinned_strip() + "\n")
    for name, (points, faces) in (("torus", torus()), ("bumpy-sphere", bumpy_sphere())):
        write_ply(os.path.join(ROOT, "tests/fixtures/hairs/%s.ply" % name), points, faces,
                  "%s made by scripts/make-meshes.py" % name)
    print("leaf.ply: %d triangles; body.obj: %d triangles; bird.obj: %d triangles"
          % (len(triangles), len(faces), len(bird[3])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
