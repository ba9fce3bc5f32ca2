/* A close-up of the middle of the Nankin cherry bough: the felt on the twigs, the fringe on the leaf edges. */
#include "nankin-cherry.v"
scale factor: 4
