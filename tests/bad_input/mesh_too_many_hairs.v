surface: B mesh_too_many_hairs.obj 1
