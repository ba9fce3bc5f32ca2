/* A flatbed scanner's view of a feather lying front up on the glass: from below, parallel, on a
   plain background. The scanner sees the feather's back: the turtle's up vector (the front)
   points away from the viewer, the left vane is on the picture's left. */
projection: parallel
viewpoint: 0,0,1
view reference point: 0,0,0
scale factor: 0.9
render mode: shaded
light: V: 0.3,0.6,1 D: 1,1,1

/* 1: the hawk's tail feather as it was scanned; 2: the type read back from the scan. */
feather: hawk.fea
feather: found.fea
