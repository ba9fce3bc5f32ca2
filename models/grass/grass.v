/* View of the grass tuft: cylinders lit by one light, materials from grass.mat. */
angle increment: 30
initial color: 1
initial line width: 0.1
line style: cylinder
contour sides: 10
viewpoint: 0.4,0.3,1
view reference point: 0,0,0
projection: parallel
scale factor: 0.9
render mode: shaded
light: V: 1,2,2 D: 1,1,1
