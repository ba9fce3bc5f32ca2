/* View of side-curvature.l. */
#include "row.v"
feather: base.fea
feather: side-0.fea
feather: side-02.fea
feather: side-04.fea
feather: side-m02.fea
