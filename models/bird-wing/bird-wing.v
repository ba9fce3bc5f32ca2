/* The wing seen from above and behind, lit from above; the flight feathers of the
   feather-types model. */
angle increment: 90
projection: parallel
viewpoint: 0.2,-0.6,1
view reference point: 0,0,0
scale factor: 0.9
z buffer: on
render mode: shaded
line style: cylinder
contour sides: 10
light: V: 0.3,0.4,1 D: 1,1,1
feather: flight.fea

/* The dynamics (docs/dynamics.md), in centimetres and seconds. */
dynamics gravity: 0 0 -981
dynamics springs: 50000 300
dynamics drag: 0.5
dynamics thickness: 0.3 0.05
dynamics substeps: 4
