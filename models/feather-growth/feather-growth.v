/* View of the growth sequence (Streit & Heidrich 2002, Fig. 7). */
angle increment: 90
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light: V: 0.3,0.6,1 D: 1,1,1

feather: contour.fea
