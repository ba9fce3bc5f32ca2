surface: B mesh_missing.obj 1
