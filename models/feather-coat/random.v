/* View of the feather coat on pseudo-random follicles (Streit & Heidrich 2002, Fig. 16). */
#include "coat.v"
feather follicles: diffusion
