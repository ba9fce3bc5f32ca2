surface: B mesh_nan.obj 1
