/* The furry square, dry, seen from above its front. */
angle increment: 90
line style: cylinder
contour: 1 flat.con
projection: parallel
viewpoint: -1,0.25,0.35
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light direction: -0.3,1,0.4

fur layers: 16
fur texture: 256 3 12
