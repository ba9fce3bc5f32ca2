/* A close-up of the middle of the poppy rosette: young leaflets densely hairy, old ones with edge hairs only, the bud with its near-tangent bristles. */
angle increment: 45
initial color: 1
initial line width: 0.5
line style: cylinder
contour sides: 10
projection: parallel
viewpoint: 0,0.55,1
view reference point: 0,0,0
scale factor: 2.6
z buffer: on
render mode: shaded
light: V: 0.5,1,0.8 D: 1,1,0.95
light: V: -0.4,0.3,-1 D: 0.25,0.25,0.3
function set: oriental-poppy.fset
contour: 1 leaflet.con

hair: straight.l
hair: curved.l
hair texture: 100 11
hair interpolation: on
