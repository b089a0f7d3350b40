// atomic_file.cpp — temporary + fsync + rename (atomic_file.hpp).
#include "haptics/atomic_file.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace contactlab {

void write_file_atomically(const std::string& path, std::string_view text) {
    std::string tmp = path + ".tmp-XXXXXX";
    const int fd = ::mkstemp(tmp.data());
    if (fd < 0) throw FileWriteError(path + ": cannot create temporary file (" + std::strerror(errno) + ")");
    const char* p = text.data();
    std::size_t left = text.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = errno;
            ::close(fd);
            ::unlink(tmp.c_str());
            throw FileWriteError(path + ": write failed (" + std::strerror(err) + ")");
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    ::fchmod(fd, 0644);
    // close() must run even when fsync() fails, or every failed save leaks a descriptor.
    const int sync_rc = ::fsync(fd);
    const int sync_err = errno;
    const int close_rc = ::close(fd);
    if (sync_rc != 0 || close_rc != 0) {
        const int err = sync_rc != 0 ? sync_err : errno;
        ::unlink(tmp.c_str());
        throw FileWriteError(path + ": flush failed (" + std::strerror(err) + ")");
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(tmp.c_str());
        throw FileWriteError(path + ": cannot replace file (" + std::strerror(err) + ")");
    }
}

}  // namespace contactlab
