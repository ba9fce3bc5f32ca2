/* View of silhouette.l. */
#include "row.v"
feather: base.fea
feather: length-08.fea
feather: length-16.fea
feather: silhouette-narrow.fea
feather: silhouette-step.fea
