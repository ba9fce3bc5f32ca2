/* View of feather-material.l: materials from feather-material.mat. */
angle increment: 90
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
scale factor: 0.95
z buffer: on
render mode: shaded
light: V: 0.3,0.6,1 D: 1,1,1
feather: material-1.fea
feather: material-2.fea
feather: material-3.fea
