/* The four furry squares of Fig. 7, seen from their fur's side. */
angle increment: 90
line style: cylinder
contour: 1 flat.con
projection: parallel
viewpoint: -1,0.5,0.3
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light direction: -0.2,1,0.5

fur layers: 32
fur texture: 256 11 12
