executable: density field.spec
communication type: pipes
turtle position:P:%g %g %g
