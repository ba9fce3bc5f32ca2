/* The pussy-willow twig, dry; wet.v adds rain. */
angle increment: 90
line style: cylinder
contour sides: 24
projection: parallel
viewpoint: 0,0.2,1
view reference point: 0,0,0
scale factor: 0.9
z buffer: on
render mode: shaded
light direction: 0.6,0.8,0.5
diffuse reflection: 0

fur layers: 24
fur texture: 256 5 14
