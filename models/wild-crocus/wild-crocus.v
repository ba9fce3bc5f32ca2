/* View of the wild crocus, from the side and a little above. */
angle increment: 45
initial color: 2
initial line width: 0.3
line style: cylinder
contour sides: 10
projection: parallel
viewpoint: 0,0.35,1
view reference point: 0,0,0
scale factor: 0.92
z buffer: on
render mode: shaded
light: V: 0.6,1,0.7 D: 1,1,0.95
light: V: -0.5,0.2,-1 D: 0.4,0.4,0.45
function set: wild-crocus.fset
contour: 1 sepal.con

hair: straight.l
hair: wavy.l
hair: wispy.l
hair texture: 100 5
hair interpolation: on
