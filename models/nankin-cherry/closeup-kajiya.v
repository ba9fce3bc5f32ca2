/* The close-up with the hairs shaded by Kajiya and Goldman's model, as in the paper, instead of
   the fibre model (docs/trace.md, "Hairs as fibres"). */
#include "closeup.v"
fibre: hairs kajiya
