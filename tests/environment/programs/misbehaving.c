/* An environmental program that goes wrong in the way its argument names: `die` exits at the
   first query, `hang` never answers, `garbage`, `open` and `unclosed` answer lines that are no
   answer records (words; an id that is no number; parentheses left open),
   `spawn` starts a child that never ends (its process id in child.pid) and answers garbage. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "comm_lib.h"

static const char* mode = "";

void Message(const char* format, ...) {
  va_list args;
  va_start(args, format);
  vfprintf(stderr, format, args);
  va_end(args);
}

static int AnswerQuery(Cmodule_type* two_modules, CTURTLE* turtle) {
  (void)two_modules;
  (void)turtle;
  if (strcmp(mode, "die") == 0) exit(3);
  if (strcmp(mode, "hang") == 0) {
    for (;;) pause();
  }
  if (strcmp(mode, "open") == 0) {
    CSSendString(0, "zz E(1,2\n");
  } else if (strcmp(mode, "unclosed") == 0) {
    CSSendString(0, "1 E((((\n");
  } else {
    CSSendString(0, "the answer is blowing in the wind\n");
  }
  return 0;
}

int main(int argc, char** argv) {
  CSInitialize(&argc, &argv);
  if (argc == 2) mode = argv[1];
  if (strcmp(mode, "spawn") == 0) {
    const pid_t child = fork();
    if (child == 0) {
      for (;;) pause();
    }
    FILE* out = fopen("child.pid", "w");
    if (out) {
      fprintf(out, "%d\n", (int)child);
      fclose(out);
    }
  }
  CSMainLoop(AnswerQuery);
  CTerminate();
  return 0;
}
