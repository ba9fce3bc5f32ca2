feather: feather_negative_length.fea
