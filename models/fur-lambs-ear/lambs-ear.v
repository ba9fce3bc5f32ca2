/* View of the furry lamb's ear: from the side and a little above. */
angle increment: 45
initial color: 1
line style: cylinder
contour sides: 12
projection: parallel
viewpoint: 0.2,0.45,1
view reference point: 0,0,0
scale factor: 1.25
z buffer: on
render mode: shaded
light: V: 0.5,1,0.8 D: 1,1,1
surface: l leaf.s 1 8 8

fur layers: 20
fur texture: 256 4 10
