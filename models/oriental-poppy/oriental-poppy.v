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

/* hirsute render --trace (docs/trace.md): sun from above and in front, a bluish sky; the
   leaflets pass some light and show their veins; the bristles catch the light white. */
trace light: D: 0.5,1,0.8 A: 5 I: 3.2,3.1,2.9
trace sky: 0.28,0.31,0.38
translucency: 1 0.3
translucency: 3 0.3
veins: 1 particles C: 0.55,0.66,0.42 W: 0.012 B: 0.5 K: 0.6
veins: 3 particles C: 0.55,0.66,0.42 W: 0.012 B: 0.5 K: 0.6
hair shading: B: 0.4 R: 0.25 S: 0.1
