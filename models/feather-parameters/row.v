/* The view shared by the rows of feathers: each model's view includes it and names its feather
   types, numbered in order for @Fe(k). */
angle increment: 90
initial color: 1
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light: V: 0.3,0.6,1 D: 1,1,1
