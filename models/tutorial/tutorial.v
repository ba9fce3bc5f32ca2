/* The view of the tutorial's plant (docs/tutorial.md): the turtle's angles and widths, the
   camera, how segments are drawn, and the light. */
angle increment: 30
initial color: 1
initial line width: 0.1
line style: cylinder
contour sides: 8
viewpoint: 0,0,1
view reference point: 0,0,0
projection: parallel
scale factor: 0.9
z buffer: on
render mode: shaded
light: V: 1,1,2 D: 1,1,1
