/* View of front-curvature.l. */
#include "row.v"
feather: base.fea
feather: front-0.fea
feather: front-02.fea
feather: front-m02.fea
