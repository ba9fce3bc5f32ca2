/* View of coat-density.l. */
#include "coat.v"
