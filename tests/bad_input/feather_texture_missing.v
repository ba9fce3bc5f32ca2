feather: feather_texture_missing.fea
