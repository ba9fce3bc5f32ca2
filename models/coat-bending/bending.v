/* The bending coat, seen from the side so that the bend shows; the feather coat model's
   contour and feather types. */
angle increment: 90
projection: parallel
viewpoint: 0.9,0.6,1
view reference point: 0,0,0
scale factor: 0.9
z buffer: on
render mode: shaded
line style: cylinder
contour: 1 strip.con
light: V: 0.3,0.6,1 D: 1,1,1
feather follicles: hexagonal
feather: brown.fea
feather: grey.fea
feather: green.fea
feather: blue.fea

/* The dynamics (docs/dynamics.md), in the model's units and seconds: stiff feathers that gravity bends a little, pressed together where the body bends. */
dynamics gravity: 0 -9.81 0
dynamics springs: 20000 100
dynamics drag: 0.2
dynamics thickness: 0.01 0.002
dynamics substeps: 4
