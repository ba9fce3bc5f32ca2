/* The close-up lit by an evening garden alone (docs/trace.md, "Environment map"): the HDR map
   garden-evening.exr (made by scripts/make-environment-map.py), its low sun to the left, seen
   behind the flowers; the spherical light of the view is switched off. */
#include "closeup.v"
trace environment: garden-evening.exr
trace light: I: 0,0,0
trace tone: filmic
