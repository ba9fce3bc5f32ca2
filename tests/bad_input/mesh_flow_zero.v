surface: B mesh_flow_zero.obj 1
mesh flow: B 0 0 0
