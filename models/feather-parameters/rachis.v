/* View of rachis.l. */
#include "row.v"
feather: base.fea
feather: rachis-short.fea
feather: rachis-long.fea
feather: rachis-wide.fea
