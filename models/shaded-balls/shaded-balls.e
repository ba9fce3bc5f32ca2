executable: chiba -e shaded-balls.e light.spec
communication type: pipes
turtle position:P:%.4g %.4g %.4g
verbose: off
