/* View of spacing.l. */
#include "row.v"
feather: base.fea
feather: spacing-012.fea
feather: spacing-025.fea
feather: spacing-tip.fea
