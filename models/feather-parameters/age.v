/* View of age.l. */
#include "row.v"
feather: base.fea
