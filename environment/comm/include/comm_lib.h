/* Hirsute's communication library for environmental programs: the slave side of cpfg's
   protocol for open L-systems, with the declarations of the comm_lib.h that programs written
   for vlab's library include (the same structures, the same functions), so that such programs
   build against it unchanged. The program supplies Message(format, ...), through which the
   library reports problems. */
#ifndef __COMM_LIB_H__
#define __COMM_LIB_H__

#define CMAXPARAMS 20   /* parameters of a module */
#define CMAXSYMBOLLEN 4 /* characters of a module's symbol (@Gs) */
#define CMAXFIELDS 20   /* environmental processes */

/* A module: its symbol and parameters; `set` marks the values a program answers with. */
struct module_type {
  char symbol[CMAXSYMBOLLEN + 1];
  int num_params;
  struct param_type {
    float value;
    char set;
  } params[CMAXPARAMS];
};
typedef struct module_type Cmodule_type;

/* The turtle values sent with a query, each with the number of values its .e format has. */
struct CTURTLE {
  float position[3];
  int positionC;
  float heading[3];
  int headingC;
  float left[3];
  int leftC;
  float up[3];
  int upC;
  float line_width;
  int line_widthC;
  float scale_factor;
  int scale_factorC;
};
typedef struct CTURTLE CTURTLE;

#define CMIN_MASTER_INDEX 0

#ifdef __cplusplus
extern "C" {
#endif

/* The slave side (an environmental program). */
void CSInitialize(int* argc, char*** argv);
int CSBeginTransmission(void);
void CSMainLoop(int (*AnswerQuery)(Cmodule_type*, CTURTLE*));
int CSEndTransmission(void);
void CSTerminate(void);

void CTerminate(void);
int CShouldTerminate(void);

int CSGetNumberOfMasters(void);
int CSGetData(int* master, unsigned long* distance, Cmodule_type* two_modules, CTURTLE* turtle);
void CSSendData(int master, unsigned long dist, Cmodule_type* comm_symbol);
int CSGetString(int* master, char* str, int length);
int CSSendString(int index, char* item);

/* Supplied by the program. */
void Message(const char* format, ...);

#ifdef __cplusplus
}
#endif

#endif
