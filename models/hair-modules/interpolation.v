/* The interpolation example: the view of every example, with `hair interpolation: on`. */
#include "hair-modules.v"
hair interpolation: on
