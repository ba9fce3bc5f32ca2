/* View of afterfeather.l. */
#include "row.v"
feather: base.fea
feather: afterfeather-04.fea
feather: afterfeather-07.fea
