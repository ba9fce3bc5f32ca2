/* View of the herb. Derivation reads only the function set; the rest is for rendering. */
angle increment: 45
initial color: 1
color increment: 1
initial line width: 1
line width increment: 0.01
viewpoint: 0,0,1
view reference point: 0,0,0
projection: parallel
scale factor: 0.9
z buffer: on
render mode: shaded
line style: cylinder
contour sides: 8
light: V: 1,1,2 D: 1,1,1
function set: herb.fset
surface: l leaf.s 1.5
