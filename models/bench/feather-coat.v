/* The feather-coat benchmark: the types and view of models/feather-coat. */
angle increment: 90
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
z buffer: on
render mode: shaded
line style: cylinder
contour: 1 ../feather-coat/strip.con
feather: ../feather-coat/brown.fea
feather: ../feather-coat/grey.fea
feather: ../feather-coat/green.fea
feather: ../feather-coat/blue.fea
