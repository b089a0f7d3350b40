// data_path.cpp — see data_path.hpp.
#include "engine/app/data_path.hpp"

#include <filesystem>
#include <system_error>

namespace contactlab::app {

std::string installed_data_path(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path given(path);
    if (path.empty() || given.is_absolute() || fs::exists(given, ec)) return path;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return path;
    const fs::path installed = exe.parent_path().parent_path() / "share" / "contactlab" / given;
    return fs::is_regular_file(installed, ec) ? installed.string() : path;
}

}  // namespace contactlab::app
