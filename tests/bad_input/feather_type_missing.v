feather: nowhere.fea
