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
function set: herb.fset
