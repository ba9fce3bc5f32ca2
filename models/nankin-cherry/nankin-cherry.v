/* View of the Nankin cherry bough, lit from behind (the fuzz glows at the leaf edges). */
angle increment: 45
initial color: 3
initial line width: 0.5
line style: cylinder
contour sides: 10
projection: parallel
viewpoint: 0.15,0.1,1
view reference point: 0,0,0
scale factor: 0.92
z buffer: on
render mode: shaded
light: V: -0.3,0.6,-1 D: 1,0.95,0.85
light: V: 0.3,0.5,1 D: 0.45,0.45,0.5
function set: nankin-cherry.fset
contour: 1 leaf.con

hair: straight.l
hair: bent.l
hair: curled.l
hair texture: 100 3
hair interpolation: on

/* hirsute render --trace (docs/trace.md): backlit as in Fig. 5 of the paper, the light nearly
   behind the bough as the sun in the photograph of Fig. 1, a dim sky, leaves that pass light
   through; the hairs are fibres that pass most of it on forwards (`fibre: hairs chiang`).
   `hair shading:` is for Kajiya and Goldman's model, which closeup-kajiya.v chooses. */
trace light: D: -0.15,0.16,-1 A: 6 I: 4,3.9,3.6
fibre: hairs chiang
trace sky: 0.06,0.07,0.09
translucency: 4 0.45
hair shading: B: 0.25 R: 0.2 S: 0.06
/* Pinnate veins on the leaves, traced by particles that merge on their way to the midrib
   (Rodkaew et al.), lighter than the blade and raised (docs/trace.md, "Veins"). */
veins: 4 particles C: 0.6,0.72,0.36 W: 0.01 B: 0.6 K: 0.75
