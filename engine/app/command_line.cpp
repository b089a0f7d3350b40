// command_line.cpp — the command line as typed (command_line.hpp).
#include "engine/app/command_line.hpp"

#include <fstream>
#include <sstream>

namespace contactlab::app {

std::string command_line() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    std::string c = s.str();
    while (!c.empty() && c.back() == '\0') c.pop_back();
    for (char& ch : c)
        if (ch == '\0') ch = ' ';
    return c;
}

}  // namespace contactlab::app
