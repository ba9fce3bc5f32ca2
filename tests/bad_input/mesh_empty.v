surface: B mesh_empty.stl 1
