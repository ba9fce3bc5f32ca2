line style: cylinder
hair: hair_template_broken.inc
