/* The close-up with light walking inside the sepals (docs/trace.md, "Light inside leaves and
   petals"): a sheet 0.3 mm thick (the model is in centimetres) whose light scatters every
   0.08 mm, instead of the diffuse transmission of `translucency:`. */
#include "closeup.v"
subsurface: 5 M: 0.008 H: 0.03
