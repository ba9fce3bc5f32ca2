executable: clover ground.spec
communication type: memory
turtle position:P:%g %g %g
