/* Feather grass in gusty wind (docs/dynamics.md, `hirsute simulate`): the view of
   feather-grass.v, and the air the awns move in. Units are centimetres and seconds. */
#include "feather-grass.v"
dynamics gravity: 0 -981 0
dynamics wind: 120 0 30
dynamics gusts: 250 12 0.7 7
dynamics drag: 0.05
dynamics springs: 1000000 2000
dynamics segments: 10
dynamics substeps: 4
