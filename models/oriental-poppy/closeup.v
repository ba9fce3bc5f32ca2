/* A close-up of the middle of the poppy rosette: young leaflets densely hairy, old ones with edge hairs only, the bud with its near-tangent bristles. */
#include "oriental-poppy.v"
scale factor: 2.6
