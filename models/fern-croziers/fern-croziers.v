/* View of the fern croziers, from the side. */
angle increment: 45
initial color: 2
initial line width: 0.5
line style: cylinder
contour sides: 12
projection: parallel
viewpoint: 0,0.25,1
view reference point: 0,0,0
scale factor: 0.92
z buffer: on
render mode: shaded
light: V: 0.6,1,0.8 D: 1,1,0.95
light: V: -0.5,0.2,-1 D: 0.4,0.4,0.45
function set: fern-croziers.fset

hair: scale.l
hair: broad.l
hair: hairlike.l
hair texture: 100 9
hair interpolation: on
