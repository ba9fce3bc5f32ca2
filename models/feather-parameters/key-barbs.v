/* View of key-barbs.l. */
#include "row.v"
feather: keys-none.fea
feather: keys-one.fea
feather: base.fea
feather: keys-several.fea
feather: keys-step.fea
