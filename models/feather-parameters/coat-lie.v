/* View of coat-lie.l. */
#include "coat.v"
