/* The nodding bird: the coat of bird.l on a mesh sequence (nod.0001.obj to nod.0012.obj) that
   `hirsute simulate` plays frame by frame, the roots following its triangles. */
angle increment: 90
projection: parallel
viewpoint: 1,0.45,0.3
view reference point: 0,0,0
scale factor: 0.9
z buffer: on
render mode: shaded
light: V: 0.3,0.6,1 D: 1,1,1

/* a mesh sequence: #### is the frame number */
surface: B nod.####.obj 1

feather follicles: diffusion
feather: brown.fea
feather: grey.fea
feather: green.fea
feather: blue.fea

/* The dynamics (docs/dynamics.md): stiff feathers in a gusty wind. */
dynamics gravity: 0 -9.81 0
dynamics springs: 20000 100
dynamics drag: 0.2
dynamics thickness: 0.01 0.002
dynamics substeps: 4
