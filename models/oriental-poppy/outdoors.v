/* The poppy rosette outdoors (docs/trace.md, "Sun and sky"): Preetham's clear sky at turbidity
   3, the sun 35 degrees up behind the plant and to its right, over a ground of bare earth. */
#include "oriental-poppy.v"
trace sun: E: 35 A: 140 T: 3 G: 0.2
trace ground: 0.3,0.24,0.16
trace tone: filmic
trace exposure: 0.5
