// Finding a program the way the shell finds it on PATH, before a fork, so that the child only
// calls exec: the C preprocessor a model runs through, GNU parallel and POV-Ray for
// `hirsute render-frames`.
#pragma once

#include <string>

namespace hirsute {

// The executable `program` on PATH (a name with a slash is taken as it is); empty when there is
// none. An unset or empty PATH searches /usr/local/bin, /usr/bin and /bin.
std::string findOnPath(const std::string& program);

}  // namespace hirsute
