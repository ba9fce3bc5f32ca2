/* The interpolation example: hair-modules.v with `hair interpolation: on`. */

angle increment: 90
initial color: 1
line style: cylinder
contour sides: 16
twist of cylinders: off
projection: parallel
viewpoint: 0,0.8,1
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light: V: 0.4,1,1 D: 1,1,1
function set: hair-modules.fset
contour: 1 strip.con

hair: straight.l
hair: curly.l
hair interpolation: on
