/* the model has one fur surface */
line style: cylinder
droplet: 0.5 0.5 0.1 1 3
