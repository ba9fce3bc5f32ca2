/* The slave side of cpfg's environment protocol (Hirsute's own implementation of the API in
   comm_lib.h). An environmental program calls CSInitialize first: it takes the options cpfg
   adds to the command line (-e FILE.e, -k KEY, -ext EXTENSION, -h HOST) out of argv, reads the
   .e file for what each query record holds, and connects over files (System V semaphores and
   the .to_field/.from_field files), shared memory, or its standard input and output (pipes,
   when started without -k). Queries are read with CSGetData and answered with CSSendData, a
   batch at a time between CSBeginTransmission and CSEndTransmission; CSMainLoop does all of it.
   The text is the one in the specification of the protocol (records, `Control:` lines). */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ipc.h>
#include <sys/sem.h>
#include <sys/shm.h>
#include <unistd.h>

#include "comm_lib.h"

enum { TO_SLAVE_BYTES = 50000, FROM_SLAVE_BYTES = 10000 };
enum { POSITION, HEADING, LEFT, UP, LINE_WIDTH, SCALE_FACTOR, TURTLE_VALUES };
enum { PIPES, FILES, MEMORY };

static const char* const turtle_keywords[TURTLE_VALUES] = {
    "turtle position", "turtle heading",    "turtle left",
    "turtle up",       "turtle line width", "turtle scale factor"};

static struct {
  int transport;
  int following_module;
  int present[TURTLE_VALUES];
  int conversions[TURTLE_VALUES];
  size_t skip[TURTLE_VALUES];
  float stale[TURTLE_VALUES][3];
  int semaphores;
  char* memory;
  char to_field[512], from_field[512];
  /* The batch being read (files, memory), and the answers being written. */
  char* in;
  size_t in_size, in_at;
  char* out;
  size_t out_size, out_capacity;
  int batch_over;
  int terminate;
} comm = {PIPES, 1, {0}, {0}, {0}, {{0}}, -1, NULL, "", "", NULL, 0, 0, NULL, 0, 0, 0, 0};

static void append(const char* text, size_t n) {
  if (comm.out_size + n + 1 > comm.out_capacity) {
    size_t capacity = comm.out_capacity ? comm.out_capacity : 4096;
    while (comm.out_size + n + 1 > capacity) capacity *= 2;
    char* grown = realloc(comm.out, capacity);
    if (grown == NULL) {
      Message("communication library: out of memory\n");
      exit(1);
    }
    comm.out = grown;
    comm.out_capacity = capacity;
  }
  memcpy(comm.out + comm.out_size, text, n);
  comm.out_size += n;
  comm.out[comm.out_size] = '\0';
}

/* The number of conversions in a format (each % not followed by %, at most 3) and the offset
   of the first. */
static void read_format(const char* format, int* count, size_t* first) {
  *count = 0;
  *first = 0;
  for (size_t i = 0; format[i] != '\0'; ++i) {
    if (format[i] != '%') continue;
    if (format[i + 1] == '%') {
      ++i;
      continue;
    }
    if (*count == 0) *first = i;
    if (*count < 3) ++*count;
  }
}

static void read_communication_file(const char* name) {
  FILE* f = fopen(name, "r");
  if (f == NULL) {
    Message("communication library: cannot open %s\n", name);
    exit(1);
  }
  char line[4097];
  while (fgets(line, sizeof line, f) != NULL) {
    line[strcspn(line, "\n")] = '\0';
    const size_t end = strcspn(line, ":\t");
    const char* rest = line[end] == '\0' ? line + end : line + end + 1;
    char keyword[4097];
    memcpy(keyword, line, end);
    keyword[end] = '\0';
    char word[64] = "";
    sscanf(rest, " %63[^ \t:]", word);
    if (strcmp(keyword, "communication type") == 0) {
      if (strcmp(word, "memory") == 0) comm.transport = MEMORY;
      if (strcmp(word, "files") == 0) comm.transport = FILES;
    } else if (strcmp(keyword, "following module") == 0) {
      comm.following_module = strcmp(word, "no") != 0;
    } else {
      for (int v = 0; v < TURTLE_VALUES; ++v) {
        if (strcmp(keyword, turtle_keywords[v]) != 0) continue;
        comm.present[v] = 1;
        read_format(rest, &comm.conversions[v], &comm.skip[v]);
      }
    }
  }
  fclose(f);
}

static void semaphore(int which, int change) {
  struct sembuf op = {(unsigned short)which, (short)change, 0};
  while (semop(comm.semaphores, &op, 1) != 0) {
    if (errno == EINTR) continue;
    /* The master removed the semaphores: it has gone. */
    exit(0);
  }
}

void CSInitialize(int* argc, char*** argv) {
  const char *efile = NULL, *extension = NULL;
  int key = -1, remote = 0;
  int kept = 1;
  for (int i = 1; i < *argc; ++i) {
    const char* a = (*argv)[i];
    if (i + 1 < *argc && strcmp(a, "-e") == 0) {
      efile = (*argv)[++i];
    } else if (i + 1 < *argc && strcmp(a, "-ext") == 0) {
      extension = (*argv)[++i];
    } else if (i + 1 < *argc && strcmp(a, "-k") == 0) {
      key = atoi((*argv)[++i]);
    } else if (i + 1 < *argc && strcmp(a, "-h") == 0) {
      ++i;
      remote = 1;
    } else {
      (*argv)[kept++] = (*argv)[i];
    }
  }
  *argc = kept;
  (*argv)[kept] = NULL;
  if (efile != NULL) read_communication_file(efile);
  if (remote) {
    Message("communication library: sockets (-h) are not supported\n");
    exit(1);
  }
  if (key < 0) {
    /* Started without a key: pipes. The master waits for one byte of value 1. */
    comm.transport = PIPES;
    fputc(1, stdout);
    fflush(stdout);
    return;
  }
  if (comm.transport == PIPES) comm.transport = extension != NULL ? FILES : MEMORY;
  comm.semaphores = semget(key, 2, 0);
  if (comm.semaphores < 0) {
    Message("communication library: no semaphores for key %d\n", key);
    exit(1);
  }
  if (comm.transport == MEMORY) {
    const int segment = shmget(key - 1, TO_SLAVE_BYTES + FROM_SLAVE_BYTES, 0);
    void* at = segment < 0 ? (void*)-1 : shmat(segment, NULL, 0);
    if (at == (void*)-1) {
      Message("communication library: no shared memory for key %d\n", key);
      exit(1);
    }
    comm.memory = at;
  } else {
    snprintf(comm.to_field, sizeof comm.to_field, ".to_field%s", extension ? extension : "");
    snprintf(comm.from_field, sizeof comm.from_field, ".from_field%s", extension ? extension : "");
  }
  /* Tell the master that the program runs. */
  semctl(comm.semaphores, 1, SETVAL, 0);
}

int CSGetNumberOfMasters(void) {
  return 1;
}

int CShouldTerminate(void) {
  return comm.terminate;
}

int CSBeginTransmission(void) {
  comm.out_size = 0;
  comm.batch_over = 0;
  if (comm.transport == PIPES) return 1;
  semaphore(0, -1);
  free(comm.in);
  comm.in = NULL;
  comm.in_size = comm.in_at = 0;
  if (comm.transport == MEMORY) {
    comm.in_size = strnlen(comm.memory, TO_SLAVE_BYTES);
    comm.in = malloc(comm.in_size + 1);
    if (comm.in == NULL) exit(1);
    memcpy(comm.in, comm.memory, comm.in_size);
    comm.in[comm.in_size] = '\0';
    return 1;
  }
  FILE* f = fopen(comm.to_field, "rb");
  if (f == NULL) {
    Message("communication library: cannot read %s\n", comm.to_field);
    exit(1);
  }
  size_t capacity = 0;
  for (;;) {
    if (comm.in_size + 4096 + 1 > capacity) {
      capacity = capacity ? capacity * 2 : 65536;
      char* grown = realloc(comm.in, capacity);
      if (grown == NULL) exit(1);
      comm.in = grown;
    }
    const size_t n = fread(comm.in + comm.in_size, 1, 4096, f);
    comm.in_size += n;
    if (n == 0) break;
  }
  fclose(f);
  comm.in[comm.in_size] = '\0';
  return 1;
}

/* The next line of the batch, without its newline, in a buffer of the library's (NULL at the
   end of the input). */
static char* next_line(void) {
  static char* line = NULL;
  static size_t capacity = 0;
  if (comm.transport == PIPES) {
    const ssize_t n = getline(&line, &capacity, stdin);
    if (n < 0) return NULL;
    line[strcspn(line, "\n")] = '\0';
    return line;
  }
  if (comm.in == NULL || comm.in_at >= comm.in_size) return NULL;
  const char* start = comm.in + comm.in_at;
  const size_t length = strcspn(start, "\n");
  if (length + 1 > capacity) {
    capacity = length + 1;
    char* grown = realloc(line, capacity);
    if (grown == NULL) exit(1);
    line = grown;
  }
  memcpy(line, start, length);
  line[length] = '\0';
  comm.in_at += length + (start[length] == '\n');
  return line;
}

/* A module at *at: one character (two for ~ and @) and its parameters between ( and ). */
static void read_module(const char** at, Cmodule_type* m) {
  memset(m, 0, sizeof *m);
  const char* p = *at;
  if (*p == '\0') return;
  int length = 0;
  m->symbol[length++] = *p++;
  if ((m->symbol[0] == '~' || m->symbol[0] == '@') && *p != '\0') m->symbol[length++] = *p++;
  m->symbol[length] = '\0';
  if (*p == '(') {
    ++p;
    for (;;) {
      const size_t piece = strcspn(p, ",)");
      if (m->num_params < CMAXPARAMS) {
        struct param_type* param = &m->params[m->num_params++];
        if (piece > 0) {
          char number[64];
          const size_t n = piece < sizeof number - 1 ? piece : sizeof number - 1;
          memcpy(number, p, n);
          number[n] = '\0';
          param->value = (float)atof(number);
          param->set = 1;
        }
      }
      p += piece;
      if (*p != ',') break;
      ++p;
    }
    if (*p == ')') ++p;
  }
  *at = p;
}

int CSGetData(int* master, unsigned long* distance, Cmodule_type* two_modules, CTURTLE* turtle) {
  *master = CMIN_MASTER_INDEX;
  if (comm.batch_over) return 0;
  const char* line = next_line();
  if (line == NULL) {
    /* The master has gone. */
    comm.batch_over = 1;
    comm.terminate = 1;
    return 0;
  }
  if (strncmp(line, "Control:", 8) == 0) {
    const int flags = atoi(line + 8);
    if (flags & 8) comm.terminate = 1;
    /* A part of a split batch is answered as it ends; the batch goes on after it. */
    comm.batch_over = 1;
    return 0;
  }
  *distance = strtoul(line, NULL, 10);
  const char* at = strchr(line, 'E');
  memset(&two_modules[0], 0, sizeof two_modules[0]);
  memset(&two_modules[1], 0, sizeof two_modules[1]);
  if (at != NULL) {
    read_module(&at, &two_modules[0]);
    if (comm.following_module) read_module(&at, &two_modules[1]);
  }
  float* vectors[TURTLE_VALUES] = {turtle->position, turtle->heading,     turtle->left,
                                   turtle->up,       &turtle->line_width, &turtle->scale_factor};
  int* counts[TURTLE_VALUES] = {&turtle->positionC, &turtle->headingC,    &turtle->leftC,
                                &turtle->upC,       &turtle->line_widthC, &turtle->scale_factorC};
  for (int v = 0; v < TURTLE_VALUES; ++v) {
    *counts[v] = 0;
    if (!comm.present[v]) continue;
    const char* values = next_line();
    const int n = v < LINE_WIDTH ? 3 : 1;
    if (values != NULL) {
      const char* p = values + (strlen(values) < comm.skip[v] ? strlen(values) : comm.skip[v]);
      for (int k = 0; k < n; ++k) {
        char* end;
        const float value = strtof(p, &end);
        if (end == p) break;
        comm.stale[v][k] = value;
        p = end;
      }
    }
    for (int k = 0; k < n; ++k) vectors[v][k] = comm.stale[v][k];
    *counts[v] = comm.conversions[v];
  }
  return 1;
}

void CSSendData(int master, unsigned long dist, Cmodule_type* comm_symbol) {
  (void)master;
  if (comm_symbol->num_params <= 0) return;
  char text[64];
  append(text, (size_t)snprintf(text, sizeof text, "%lu E(", dist));
  for (int i = 0; i < comm_symbol->num_params && i < CMAXPARAMS; ++i) {
    if (i > 0) append(",", 1);
    if (comm_symbol->params[i].set) {
      append(text, (size_t)snprintf(text, sizeof text, "%g", (double)comm_symbol->params[i].value));
    }
  }
  append(")\n", 2);
}

int CSGetString(int* master, char* str, int length) {
  *master = CMIN_MASTER_INDEX;
  const char* line = next_line();
  if (line == NULL || length <= 0) return 0;
  snprintf(str, (size_t)length, "%s", line);
  return 1;
}

int CSSendString(int index, char* item) {
  (void)index;
  append(item, strlen(item));
  return 1;
}

/* Answers larger than the shared memory block back go in parts, cut at line ends: each part
   but the last ends with a control line without the last-part bit (1 for the first part, 0 for
   the others); the master takes it and raises semaphore 0 for the next. The last part ends with
   `Control: 4`, or `Control: 5` when the answers fit at once. */
static void send_answers_in_parts(void) {
  enum { CONTROL_RESERVE = 16 };
  const char* const end_line = "Control: 5\n";
  const size_t end_length = strlen(end_line);
  /* The answers without the end line, which each part writes for itself. */
  const size_t body = comm.out_size - end_length;
  size_t from = 0;
  int first = 1;
  for (;;) {
    const size_t room = FROM_SLAVE_BYTES - CONTROL_RESERVE;
    const int last = body - from <= room;
    size_t to = body;
    if (!last) {
      to = from + room;
      while (to > from && comm.out[to - 1] != '\n') --to;
      if (to == from) {
        Message("communication library: an answer line is longer than the shared memory block\n");
        exit(1);
      }
    }
    const char* control = last ? (first ? "Control: 5\n" : "Control: 4\n")
                               : (first ? "Control: 1\n" : "Control: 0\n");
    char* block = comm.memory + TO_SLAVE_BYTES;
    memcpy(block, comm.out + from, to - from);
    const size_t n = to - from + strlen(control);
    memcpy(block + (to - from), control, strlen(control));
    if (n < FROM_SLAVE_BYTES) block[n] = '\0';
    semaphore(1, 1);
    if (last) return;
    /* The master has read the part: it raises semaphore 0 for the next. */
    semaphore(0, -1);
    from = to;
    first = 0;
  }
}

int CSEndTransmission(void) {
  if (comm.terminate) return 1;
  append("Control: 5\n", 11);
  if (comm.transport == PIPES) {
    fwrite(comm.out, 1, comm.out_size, stdout);
    fflush(stdout);
    return 1;
  }
  if (comm.transport == MEMORY) {
    send_answers_in_parts();
    return 1;
  } else {
    FILE* f = fopen(comm.from_field, "wb");
    if (f == NULL || fwrite(comm.out, 1, comm.out_size, f) != comm.out_size || fclose(f) != 0) {
      Message("communication library: cannot write %s\n", comm.from_field);
      exit(1);
    }
  }
  semaphore(1, 1);
  return 1;
}

void CSMainLoop(int (*AnswerQuery)(Cmodule_type*, CTURTLE*)) {
  Cmodule_type two_modules[2];
  CTURTLE turtle;
  memset(&turtle, 0, sizeof turtle);
  while (!comm.terminate) {
    CSBeginTransmission();
    int master;
    unsigned long distance;
    while (CSGetData(&master, &distance, two_modules, &turtle)) {
      if (AnswerQuery(two_modules, &turtle)) CSSendData(master, distance, &two_modules[0]);
    }
    CSEndTransmission();
  }
}

void CSTerminate(void) {
  if (comm.transport == PIPES) {
    /* The master waits for one byte when it ends the exchange. */
    fputc(1, stdout);
    fflush(stdout);
  }
  if (comm.memory != NULL) shmdt(comm.memory);
  comm.memory = NULL;
  free(comm.in);
  comm.in = NULL;
  free(comm.out);
  comm.out = NULL;
  comm.out_size = comm.out_capacity = 0;
}

void CTerminate(void) {
  CSTerminate();
}
