/* View of seed.l. */
#include "row.v"
feather: down-3.fea
feather: down-4.fea
