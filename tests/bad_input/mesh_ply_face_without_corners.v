surface: B mesh_ply_face_without_corners.ply 1
