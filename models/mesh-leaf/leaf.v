/* View of the hairy leaf mesh: its face, slightly from the side. */
angle increment: 45
initial color: 1
line style: cylinder
contour sides: 12
projection: parallel
viewpoint: -0.5,0.6,-1
view reference point: 0,0,0
scale factor: 1.0
z buffer: on
render mode: shaded
light: V: 1,1,0.6 D: 1,1,1

/* a mesh file: Assimp reads it, chosen by its name; size 1 keeps its own units */
surface: L leaf.ply 1

hair: straight.l
hair: bent.l
hair texture: 100 7
