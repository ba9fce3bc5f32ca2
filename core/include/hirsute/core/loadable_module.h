// Parts of Hirsute that link large libraries are built as modules that lie beside the program
// and are loaded when first needed (docs/design.md, "Loadable modules"): the GL drawing
// (libhirsute-drawing.so), the path tracer with Embree and OpenEXR (libhirsute-trace.so) and
// the mesh files with Assimp and CGAL (libhirsute-meshes.so), the glTF export with Assimp
// (libhirsute-gltf.so). A run that does not draw, trace, read a mesh or write glTF starts without
// loading and relocating those libraries.
#pragma once

#include <string>

namespace hirsute {

// Loads the module `fileName` (once; it stays loaded for the process's life) and returns its
// symbol `entry`. The module is the file `environmentVariable` names when it is set and not
// empty; else the one beside the running program; else the one this build made (the tests, whose
// programs lie elsewhere). Returns nullptr with `error` saying what failed, naming the file.
void* moduleEntry(const char* fileName, const char* environmentVariable, const char* entry,
                  std::string& error);

}  // namespace hirsute
