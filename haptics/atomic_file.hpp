// atomic_file.hpp — replacing a file so that nothing is ever lost: write a temporary beside the
// target, flush it to disk, then rename it over the target. Readers see the old file or the new
// one, never a torn one, even if the process dies mid-write; a failure leaves the target as it
// was and no temporary behind.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace contactlab {

// The message names the path and what failed, e.g. "out.json: cannot replace file (Permission denied)".
struct FileWriteError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Writes `text` to `path` atomically (mode 0644); throws FileWriteError.
void write_file_atomically(const std::string& path, std::string_view text);

}  // namespace contactlab
