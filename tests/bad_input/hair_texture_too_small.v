line style: cylinder
hair texture: 2 1
