/* A close-up of the tallest flower of the wild crocus: translucent, veined sepals in their
   fleece of silky hairs (the paper's Fig. 7). */
#include "wild-crocus.v"
box: x: -2.5,0.5 y: 10.2,12.6 z: -3,3
