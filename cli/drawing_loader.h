// The program reaches the GL libraries (OSMesa, libGL, GLFW, X11, LLVM) only through the drawing
// module, and Embree and OpenEXR only through the trace module, each loaded when a command that
// needs it runs (loadable_module.h): `derive`, `export` and `--version` start without them.
#pragma once

namespace hirsute::cli {

// Loads libhirsute-drawing.so from the program's own folder (or $HIRSUTE_DRAWING_MODULE), calls
// its entry point `entry` with `options` and returns its exit code. When the module or a library
// it needs cannot be loaded: a message naming it, and exit code 1.
int runInDrawingModule(const char* entry, const void* options);

// The same for libhirsute-trace.so (or $HIRSUTE_TRACE_MODULE): `render --trace`.
int runInTraceModule(const char* entry, const void* options);

}  // namespace hirsute::cli
