/* View of size.l. */
#include "row.v"
feather: base.fea
