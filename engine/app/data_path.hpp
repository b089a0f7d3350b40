// data_path.hpp — where the installed `contactlab` finds its scenes and protocols.
//
// `cmake --install` and the Debian package put the scenes/ tree under PREFIX/share/contactlab/
// and the binary in PREFIX/bin/. A relative path that does not exist from the working directory
// (e.g. `contactlab demo`'s default scenes/block.json, or `contactlab experiment run
// scenes/experiments/003-curvature.json` typed outside a checkout) is looked up there, beside the
// running executable (/proc/self/exe/../../share/contactlab/PATH).
#pragma once

#include <string>

namespace contactlab::app {

// `path` itself when it exists, is absolute or empty, or when the installed copy does not exist
// either (the caller's error then names what the user typed); otherwise the installed copy.
std::string installed_data_path(const std::string& path);

}  // namespace contactlab::app
