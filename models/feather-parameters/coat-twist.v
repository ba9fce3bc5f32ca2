/* View of coat-twist.l. */
#include "coat.v"
