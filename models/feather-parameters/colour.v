/* View of colour.l. */
#include "row.v"
feather: base.fea
feather: colour-rgb.fea
feather: colour-gold.fea
feather: colour-index.fea
