// How much memory this process may take: the machine's, or less where the address space or the
// data segment is limited (ulimit -v, -d). A stage that is about to allocate in proportion to
// a model's numbers checks its estimate against it first, so that the message names the cause
// and not only "out of memory" after seconds of swapping.
#pragma once

#include <cstddef>
#include <string>

namespace hirsute {

std::size_t memoryBudgetBytes();

// "1.6 GB", "850 MB": a size for a message.
std::string memorySizeText(double bytes);

}  // namespace hirsute
