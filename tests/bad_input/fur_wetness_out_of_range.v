/* wetness is a fraction */
droplet: 0.5 0.5 0.1 -2
