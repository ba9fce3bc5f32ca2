/* The wrapping example: the view of every example, seen along the axis. */
#include "hair-modules.v"
viewpoint: 1,0,0
