/* View of the hairy leaf: its face, slightly from the side. */
angle increment: 45
initial color: 1
initial line width: 0.2
line style: cylinder
contour sides: 14
twist of cylinders: off
projection: parallel
viewpoint: 1,0.35,0.45
view reference point: 0,0,0
scale factor: 1.35
z buffer: on
render mode: shaded
light: V: 1,1,0.6 D: 1,1,1
function set: hairy-leaf.fset
contour: 1 leaf.con

hair: straight.l
hair: bent.l
hair texture: 100 7
hair interpolation: on
