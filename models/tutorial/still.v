/* The traced still of docs/tutorial.md: the hairy plant's view, closer, lit from behind as the
   hairy-plants paper lit its stills, so that the hairs shine against the light and the leaves
   pass it through. Only `hirsute render --trace` reads the trace lines. */
#include "hairy.v"
scale factor: 1.1
trace light: D: -0.6,0.5,-0.6 A: 6 I: 4,3.9,3.6
trace sky: 0.3,0.32,0.36
translucency: 2 0.4
