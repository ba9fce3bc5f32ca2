line style: cylinder
hair: no_such_template.l
