/* The furry body, dry: 16 shells over the mesh. */
angle increment: 90
projection: parallel
viewpoint: 1,0.45,0.3
view reference point: 0,0,0
scale factor: 0.9
z buffer: on
render mode: shaded
light direction: 0.6,1,0.5

/* a mesh file: Assimp reads it, chosen by its name; size 1 keeps its own units */
surface: B body.obj 1

fur layers: 16
fur texture: 256 7 14
