// progress_bar.hpp — one line on stderr, redrawn in place, for long runs (fuzz-contact,
// experiment run): "LABEL [#####     ] DONE / TOTAL UNIT". Only when stderr is a terminal (a
// person watching); thread-safe.
#pragma once

#include <cstdint>

namespace contactlab::app {

void show_progress(const char* label, std::int64_t done, std::int64_t total, const char* unit);

}  // namespace contactlab::app
