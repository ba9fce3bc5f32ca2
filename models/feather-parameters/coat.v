/* The view shared by the coat patches: each coat model's view includes it. */
#include "row.v"
line style: cylinder
contour: 1 strip.con
feather follicles: hexagonal
feather: coat-brown.fea
feather: coat-blue.fea
