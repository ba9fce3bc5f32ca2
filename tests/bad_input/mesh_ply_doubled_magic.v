surface: B mesh_ply_doubled_magic.ply 1
