/* View of angles.l. */
#include "row.v"
feather: base.fea
feather: angles-90.fea
feather: angles-steep.fea
feather: angles-tip.fea
feather: angles-sides.fea
