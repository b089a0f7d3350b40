// progress_bar.cpp — see progress_bar.hpp.
#include "engine/app/progress_bar.hpp"

#include <cstdio>
#include <mutex>
#include <string>

#include <unistd.h>

namespace contactlab::app {

void show_progress(const char* label, std::int64_t done, std::int64_t total, const char* unit) {
    static std::mutex lock;
    static std::int64_t shown = -1;
    std::lock_guard<std::mutex> g(lock);
    if (done == shown || !isatty(fileno(stderr))) return;
    shown = done;
    constexpr int kWidth = 40;
    const int filled = total > 0 ? static_cast<int>(kWidth * done / total) : kWidth;
    std::fprintf(stderr, "\r%s [%-*s] %lld / %lld %s", label, kWidth, std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 static_cast<long long>(done), static_cast<long long>(total), unit);
    if (done >= total) std::fputc('\n', stderr);
}

}  // namespace contactlab::app
