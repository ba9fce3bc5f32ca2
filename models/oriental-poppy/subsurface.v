/* The close-up with light walking inside the leaflets (docs/trace.md, "Light inside leaves and
   petals"): sheets 0.3 mm thick whose light scatters every 0.06 mm. */
#include "closeup.v"
subsurface: 1 M: 0.006 H: 0.03
subsurface: 3 M: 0.006 H: 0.03
