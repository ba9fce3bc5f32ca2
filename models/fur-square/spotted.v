/* The furry square with two coat textures (written by scripts/make-fur-files.py): spotted.l's
   @Ut picks one by its place here, from 1. */
#include "square.v"
texture: F: stripes.png
texture: F: spots.png
