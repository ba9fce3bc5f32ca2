/* View of the pasque flower's seed head: colours from pulsatilla.map, the styles in their own
   colour, the stalk's hairs straight. */
angle increment: 30
initial color: 1
line style: cylinder
contour sides: 10
viewpoint: 0.2,0.1,1
view reference point: 0,0,0
projection: parallel
scale factor: 0.92
render mode: shaded
diffuse reflection: 0
light: V: 1,2,2 D: 1,1,1
feather: style.fea
hair texture: 100 3
