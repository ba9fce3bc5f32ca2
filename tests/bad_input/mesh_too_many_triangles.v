surface: B mesh_too_many_triangles.obj 1
