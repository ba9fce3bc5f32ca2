/* The view of the feather coat, shared by hexagonal.v and random.v, which add its follicles. */
angle increment: 90
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
line style: cylinder
contour: 1 strip.con
light: V: 0.3,0.6,1 D: 1,1,1

feather: brown.fea
feather: grey.fea
feather: green.fea
feather: blue.fea
