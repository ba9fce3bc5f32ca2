/* View of coat-sides.l. */
#include "coat.v"
