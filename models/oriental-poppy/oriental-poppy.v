/* View of the oriental poppy rosette, from the side and a little above. */
angle increment: 45
initial color: 1
initial line width: 0.5
line style: cylinder
contour sides: 10
projection: parallel
viewpoint: 0,0.55,1
view reference point: 0,0,0
scale factor: 0.92
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
