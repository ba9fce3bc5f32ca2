/* View of coat-keys.l. */
#include "coat.v"
