executable: ecosystem -e competing-plants.e plants.spec
communication type: files
turtle position:P:%.4f %.4f %.4f
