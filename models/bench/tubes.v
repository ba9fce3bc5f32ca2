/* The view of the interpretation benchmark's cylinder models (bench/interpret_bench.cpp):
   tubes.l, and branching.l when drawn as cylinders. */
line style: cylinder
contour sides: 12
initial color: 128
viewpoint: 0,5,40
view reference point: 0,10,0
projection: parallel
scale factor: 0.9
z buffer: on
render mode: shaded
diffuse reflection: 12
light direction: 1.0,1.0,1.0
