/* View of blend.l. */
#include "row.v"
feather: base.fea
feather: keys-none.fea
