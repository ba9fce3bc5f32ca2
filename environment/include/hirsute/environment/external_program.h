// An environmental program that is not built in, run as its own process and spoken to over
// cpfg's protocol (the transport the .e file names), so that programs written against vlab's
// communication library work unchanged.
#pragma once

#include <iosfwd>
#include <memory>

#include "hirsute/environment/communication_file.h"
#include "hirsute/environment/environment_program.h"

namespace hirsute {

// Starts the executable of `file` in the folder of the .e file. A program that cannot be
// started, dies, takes more than `timeoutSeconds` for a batch or answers garbage is an error
// naming it. With `log`, its command line and folder are shown there before it starts. It runs
// in a process group of its own, which is ended with it: nothing it started outlives Hirsute.
std::unique_ptr<EnvironmentProgram> startExternalProgram(const CommunicationFile& file,
                                                         int timeoutSeconds,
                                                         Diagnostics& diagnostics,
                                                         std::ostream* log = nullptr);

}  // namespace hirsute
