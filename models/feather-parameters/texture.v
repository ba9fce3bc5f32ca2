/* View of texture.l. */
#include "row.v"
feather: base.fea
feather: texture-barb.fea
feather: texture-vane.fea
feather: texture-growth.fea
