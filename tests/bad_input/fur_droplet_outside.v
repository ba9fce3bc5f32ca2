/* a droplet off the surface's parametrization */
droplet: 0.5 1.5 0.1 1
