surface: B mesh_gltf_nan.gltf 1
