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

/* hirsute render --trace (docs/trace.md): the light behind and above, so that the sepals glow
   with the light they pass and their veins (jittered points joined by splines, as the paper's
   Fig. 7) show dark in it; the hairs scatter forwards, silver at the rims. */
trace light: D: 0.3,0.5,-1 A: 6 I: 4,3.9,3.6
trace sky: 0.08,0.09,0.11
translucency: 5 0.5
translucency: 2 0.3
veins: 5 splines C: 0.3,0.12,0.5 W: 0.02 B: 0.8
hair shading: B: 0.25 R: 0.2 S: 0.06
