/* View of the competing plants (hirsute render … -e competing-plants.e). */
angle increment: 90
initial line width: 0.1
line style: cylinder
viewpoint: 0,0,10
view reference point: 0,0,0
projection: parallel
scale factor: 0.9
z buffer: on
render mode: shaded
