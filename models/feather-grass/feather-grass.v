/* View of the feather grass: leaves and culms lit by one light, colours from
   feather-grass.map, the awns in their own colour. */
angle increment: 30
initial color: 1
line style: cylinder
contour sides: 8
viewpoint: 0.3,0.25,1
view reference point: 0,0,0
projection: parallel
scale factor: 0.92
render mode: shaded
diffuse reflection: 0
light: V: 1,2,2 D: 1,1,1
feather: awn.fea
