/* The poppy rosette outdoors (docs/trace.md, "Sun and sky"): Preetham's clear sky at turbidity
   3, the sun 35 degrees up behind the plant and to its right, over a ground of bare earth; seen
   in perspective from a little above, so that the sky shows behind it. */
#include "oriental-poppy.v"
projection: perspective
viewpoint: 0,18,75
view reference point: 0,20,0
viewing angle: 45
trace sun: E: 35 A: 140 T: 3 G: 0.2
trace ground: 0.3,0.24,0.16
trace tone: filmic
trace exposure: 0.5
