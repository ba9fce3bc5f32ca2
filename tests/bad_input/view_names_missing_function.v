/* The function file is not beside the model. */
angle increment: 30
function: no_such_function.func
