// command_line.hpp — the command line as typed, for the provenance a results or power file keeps.
#pragma once

#include <string>

namespace contactlab::app {

// argv joined by spaces. Linux keeps it in /proc/self/cmdline, NUL-separated, so no argv has to be
// threaded through main(); empty where that file cannot be read.
std::string command_line();

}  // namespace contactlab::app
