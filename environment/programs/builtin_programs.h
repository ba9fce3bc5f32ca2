// The built-in environmental programs, each in its own file; environment_program.cpp picks one
// by name. Each reads its specification file as the original program does (section 5 of the
// specification) and computes in f32 where the original does.
#pragma once

#include <filesystem>
#include <memory>

#include "hirsute/environment/environment_program.h"
#include "hirsute/environment/keyword_file.h"

namespace hirsute::programs {

// The lines of the specification file named on the executable line (at most 254 characters
// each, as the originals read them); an error at that line when it is missing or unreadable.
std::vector<KeywordLine> readSpecification(const ProgramCommand& command,
                                           const CommunicationFile& file);

// floor(v) as an int, kept within reach of a grid's indices (v may lie far outside it, or be
// NaN, which counts as far below).
int floorIndex(double v);

std::unique_ptr<EnvironmentProgram> makeHonda81(const CommunicationFile& file,
                                                const ProgramCommand& command,
                                                Diagnostics& diagnostics);
std::unique_ptr<EnvironmentProgram> makeEcosystem(const CommunicationFile& file,
                                                  const ProgramCommand& command,
                                                  Diagnostics& diagnostics);
std::unique_ptr<EnvironmentProgram> makeClover(const CommunicationFile& file,
                                               const ProgramCommand& command,
                                               Diagnostics& diagnostics);
std::unique_ptr<EnvironmentProgram> makeDensity(const CommunicationFile& file,
                                                const ProgramCommand& command,
                                                Diagnostics& diagnostics);
std::unique_ptr<EnvironmentProgram> makeChiba(const CommunicationFile& file,
                                              const ProgramCommand& command,
                                              Diagnostics& diagnostics);

}  // namespace hirsute::programs
