line style: cylinder
hair: hair_template_draws_nothing.inc
