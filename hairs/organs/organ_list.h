// Every organ, one line each: the one place an organ is registered (docs/design.md, "Organs").
//
//   HIRSUTE_ORGAN_ENTRY(folder, name)
//
// `folder` is its folder under hairs/ (and under hairs/include/hirsute/hairs/); `name` the prefix
// of its entry points: nameModuleTable(), nameViewLines(), nameStage(), nameWriter(),
// nameDrawing(), nameLive() and nameTracer(), each defined in the organ's folder. The
// order of the lines is the order the turtle's tables are searched, the stages run, and the
// organs are written, drawn, made live and traced.
//
// Each registry (organ_models.cpp, organ_stages.cpp, …) expands HIRSUTE_ORGANS with a macro of
// its own; hairs/CMakeLists.txt reads the same lines to add each folder and link each organ's
// libraries (hirsute_NAME_model, …, NAME in snake case) into the registries.
#pragma once

#define HIRSUTE_ORGANS(HIRSUTE_ORGAN_ENTRY) \
  HIRSUTE_ORGAN_ENTRY(plant, plantHair)     \
  HIRSUTE_ORGAN_ENTRY(feathers, feather)    \
  HIRSUTE_ORGAN_ENTRY(fur, fur)
