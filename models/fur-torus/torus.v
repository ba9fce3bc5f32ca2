/* The furry torus, dry: straight fur, 16 layers. */
angle increment: 90
line style: cylinder
contour sides: 36
projection: parallel
viewpoint: 0,-1.2,1
view reference point: 0,0,0
scale factor: 0.92
z buffer: on
render mode: shaded
light direction: 0.5,0.4,1

fur layers: 16
fur texture: 256 7 14
