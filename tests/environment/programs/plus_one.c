/* An environmental program of a model's own, written against comm_lib.h: it answers every
   ?E(x, …) with x + 1 in the first parameter and the x coordinate of the turtle in the second,
   leaving the rest unset. Its only argument is a file it must be able to open. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "comm_lib.h"

void Message(const char* format, ...) {
  va_list args;
  va_start(args, format);
  vfprintf(stderr, format, args);
  va_end(args);
}

static int AnswerQuery(Cmodule_type* two_modules, CTURTLE* turtle) {
  Cmodule_type* e = &two_modules[0];
  for (int i = 0; i < e->num_params; ++i) e->params[i].set = 0;
  if (e->num_params > 0) {
    e->params[0].value += 1;
    e->params[0].set = 1;
  }
  if (e->num_params > 1 && turtle->positionC > 0) {
    e->params[1].value = turtle->position[0];
    e->params[1].set = 1;
  }
  return 1;
}

int main(int argc, char** argv) {
  CSInitialize(&argc, &argv);
  if (argc != 2 || fopen(argv[1], "r") == NULL) {
    fprintf(stderr, "usage: %s FILE\n", argv[0]);
    return 1;
  }
  CSMainLoop(AnswerQuery);
  CTerminate();
  return 0;
}
