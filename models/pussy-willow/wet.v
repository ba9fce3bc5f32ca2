/* The pussy-willow twig after rain: droplets on the catkins clump their fur. */
#include "pussy-willow.v"
droplet: 0.3 0.5 0.12 1
droplet: 0.75 0.35 0.1 0.8
droplet: 0.5 0.75 0.1 1
