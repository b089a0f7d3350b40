// x_server_affinity.cpp — see x_server_affinity.hpp.
#include "engine/editor/x_server_affinity.hpp"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sched.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

namespace contactlab::editor {
namespace {

// The display number of a local $DISPLAY (":99", ":0.0", "unix:1"), or -1.
int local_display_number() {
    const char* d = std::getenv("DISPLAY");
    if (!d) return -1;
    std::string s = d;
    if (s.rfind("unix:", 0) == 0) s = s.substr(4);
    if (s.empty() || s[0] != ':') return -1;  // host:N is a remote (TCP) server
    char* end = nullptr;
    const long n = std::strtol(s.c_str() + 1, &end, 10);
    return end != s.c_str() + 1 && n >= 0 && n < 65536 ? static_cast<int>(n) : -1;
}

// The pid at the other end of the display's Unix socket (SO_PEERCRED), or -1. Tries the abstract
// socket first (what Xvfb and libxcb prefer on Linux), then the file.
pid_t x_server_pid(int display) {
    const std::string path = "/tmp/.X11-unix/X" + std::to_string(display);
    for (const bool abstract : {true, false}) {
        const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd < 0) return -1;
        sockaddr_un addr{};
        addr.sun_family = AF_UNIX;
        const std::size_t offset = abstract ? 1 : 0;  // abstract names start with a NUL byte
        std::memcpy(addr.sun_path + offset, path.c_str(), path.size());
        const socklen_t len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + offset + path.size());
        pid_t pid = -1;
        if (connect(fd, reinterpret_cast<sockaddr*>(&addr), len) == 0) {
            ucred cred{};
            socklen_t cl = sizeof cred;
            if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &cl) == 0) pid = cred.pid;
        }
        close(fd);  // a connection that never speaks: the server drops it
        if (pid > 0) return pid;
    }
    return -1;
}

std::string process_name(pid_t pid) {
    std::ifstream f("/proc/" + std::to_string(pid) + "/comm");
    std::string name;
    std::getline(f, name);
    return name;
}

}  // namespace

std::string keep_x_server_off_core(int servo_core) {
    if (servo_core < 0) return "";
    const int display = local_display_number();
    if (display < 0) return "";
    const pid_t pid = x_server_pid(display);
    if (pid <= 0) return "";
    const std::string name = process_name(pid);
    if (name != "Xvfb") return "";
    int moved = 0, refused = 0;
    std::error_code ec;
    for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec)) {
        const pid_t tid = static_cast<pid_t>(std::strtol(task.path().filename().c_str(), nullptr, 10));
        cpu_set_t set;
        CPU_ZERO(&set);
        if (sched_getaffinity(tid, sizeof set, &set) != 0) { ++refused; continue; }
        if (!CPU_ISSET(servo_core, &set)) continue;
        CPU_CLR(servo_core, &set);
        if (CPU_COUNT(&set) == 0 || sched_setaffinity(tid, sizeof set, &set) != 0) { ++refused; continue; }
        ++moved;
    }
    return "Xvfb (pid " + std::to_string(pid) + ", display :" + std::to_string(display) + "): " + std::to_string(moved) +
           " thread(s) kept off the servo's CPU " + std::to_string(servo_core) +
           (refused ? ", " + std::to_string(refused) + " refused" : "");
}

}  // namespace contactlab::editor
