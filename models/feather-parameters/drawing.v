/* View of drawing.l. */
#include "row.v"
feather: base.fea
feather: drawing-lines.fea
feather: drawing-001.fea
feather: drawing-008.fea
