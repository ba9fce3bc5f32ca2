line style: cylinder
