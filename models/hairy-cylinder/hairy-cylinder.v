/* View of the hairy cylinder (Algorithm 1, Figure 3 of "Modeling Hairy Plants"). */
angle increment: 90
initial color: 1
initial line width: 1
line style: cylinder
contour sides: 24
projection: parallel
viewpoint: 0,0.35,1
view reference point: 0,0,0
scale factor: 0.9
z buffer: on
render mode: shaded
light: V: 0.4,1,1 D: 1,1,1
function set: hairy-cylinder.fset

/* the template hairs, in the order of @Hp's probabilities */
hair: straight.l
hair: curly.l
hair texture: 100 1
hair interpolation: on
