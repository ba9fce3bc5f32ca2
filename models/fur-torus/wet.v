/* The furry torus, wet: the dry view with droplets that clump the fur. */
#include "torus.v"
droplet: 0.2 0.1 0.08 1
droplet: 0.6 0.35 0.06 0.9
droplet: 0.1 0.6 0.1 1
droplet: 0.7 0.8 0.07 0.8
droplet: 0.45 0.55 0.05 1
