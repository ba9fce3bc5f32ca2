feather: feather_file_c1_controls.fea
