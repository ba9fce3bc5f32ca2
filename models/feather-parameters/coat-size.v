/* View of coat-size.l. */
#include "coat.v"
