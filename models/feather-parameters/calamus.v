/* View of calamus.l. */
#include "row.v"
feather: base.fea
feather: calamus-long.fea
feather: calamus-narrow.fea
feather: calamus-wide.fea
