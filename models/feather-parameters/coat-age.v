/* View of coat-age.l. */
#include "coat.v"
