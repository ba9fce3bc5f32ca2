/* View of the feather coat on hexagonal follicles (Streit & Heidrich 2002, Fig. 15). */
#include "coat.v"
feather follicles: hexagonal
