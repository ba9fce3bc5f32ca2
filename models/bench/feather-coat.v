/* The feather-coat benchmark: the types and view of models/feather-coat. */
angle increment: 90
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
z buffer: on
render mode: shaded
line style: cylinder
contour: 1 strip.con
feather: brown.fea
feather: grey.fea
feather: green.fea
feather: blue.fea
