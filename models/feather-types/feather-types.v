/* View of the feather types of Streit & Heidrich 2002, Figs. 10, 11 and 14, side by side. */
angle increment: 90
initial color: 1
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light: V: 0.3,0.6,1 D: 1,1,1

/* The feather types, numbered in this order for @Fe(k, ...). */
feather: contour.fea
feather: flight.fea
feather: down.fea
feather: semiplume.fea
feather: filoplume.fea
feather: bristle.fea
feather: hawk.fea
feather: budgie.fea

/* hirsute render --trace: the light of the line above (in colour-map mode it would come from
   +x, edge-on to the feathers). */
trace light: D: 0.3,0.6,1
