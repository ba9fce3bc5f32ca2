/* The view of the hairy plant (docs/tutorial.md): the plant's view, tutorial.v, and the
   template hair that every hair copies. */
#include "tutorial.v"
hair: hair.l
