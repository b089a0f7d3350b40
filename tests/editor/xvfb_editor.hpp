// xvfb_editor.hpp — runs the real `contactlab edit` under `xvfb-run -a` with lavapipe, and reads
// the `report LABEL` lines its scripts print (engine/editor/script.hpp), for the editor's tests.
#pragma once

#include "process.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace editor_test {

// xvfb-run's arguments for `contactlab ARGS`. The X authority file is ours (-f, a fresh name
// under the temporary folder): without it xvfb-run makes a temporary folder of its own and, now
// and then, fails to remove it after the command ended (twice in a row once), its exit status 5
// then replacing the editor's. `auth` is set to the file's path (the caller removes it).
inline std::vector<std::string> xvfb_args(const std::vector<std::string>& args, std::string& auth) {
    static int calls = 0;
    auth = (std::filesystem::temp_directory_path() / ("contactlab-xauth-" + std::to_string(::getpid()) + "-" + std::to_string(++calls)))
               .string();
    std::vector<std::string> all = {"-a", "-f", auth, "-s", "-screen 0 1600x1000x24", cli_test::exe_path()};
    all.insert(all.end(), args.begin(), args.end());
    return all;
}

inline cli_test::ProcessResult run_under_xvfb(std::vector<std::string> args, const std::string& cwd = {}) {
    setenv("VK_DRIVER_FILES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json", 1);
    std::string auth;
    const std::vector<std::string> all = xvfb_args(args, auth);
    // xvfb-run itself sometimes fails to remove its own temporary folder after the command ended
    // (its exit status 5 then replaces the editor's): that is the wrapper's failure, not the
    // editor's, so such a run is made once more. Any other status is the editor's.
    cli_test::ProcessResult r = cli_test::run_process("/usr/bin/xvfb-run", all, cwd, std::chrono::seconds(120));
    if (r.exit_code == 5 && r.err.find("xvfb-run: error: problem while cleaning up temporary directory") != std::string::npos)
        r = cli_test::run_process("/usr/bin/xvfb-run", all, cwd, std::chrono::seconds(120));
    std::error_code ec;
    std::filesystem::remove(auth, ec);
    return r;
}

// `contactlab edit --script SCRIPT --software --validation --timeout 100` under Xvfb, with TMPDIR
// set to `tmpdir` first (an untitled scene's recovery file lands there, out of the next test's way).
inline cli_test::ProcessResult run_validated_script(const std::string& script, const std::string& tmpdir) {
    setenv("TMPDIR", tmpdir.c_str(), 1);
    return run_under_xvfb({"edit", "--script", script, "--software", "--validation", "--timeout", "100"});
}

// Starts `xvfb-run ... contactlab ARGS` without waiting (stdout and stderr to `log`); returns the
// xvfb-run process's id. With kill_editor() below a test can kill the editor as a crash would.
inline pid_t start_under_xvfb(std::vector<std::string> args, const std::string& log) {
    setenv("VK_DRIVER_FILES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json", 1);
    std::string auth;  // left for the OS's temporary folder: the editor may outlive this call
    const std::vector<std::string> all = xvfb_args(args, auth);
    const pid_t pid = cli_test::start_process("/usr/bin/xvfb-run", all, log);
    REQUIRE(pid >= 0);
    return pid;
}

// The id of the running `contactlab` whose command line contains `marker` (e.g. its script's
// path), from /proc; 0 if none.
inline pid_t find_contactlab(const std::string& marker) {
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
        const std::string name = e.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        std::ifstream in(e.path() / "cmdline", std::ios::binary);
        std::string cmd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        for (char& c : cmd) if (c == '\0') c = ' ';
        if (cmd.rfind(cli_test::exe_path(), 0) == 0 && cmd.find(marker) != std::string::npos)
            return static_cast<pid_t>(std::stol(name));
    }
    return 0;
}

// "script report LABEL: k=v k=v ..." -> {k: v}; REQUIREs that the line exists.
inline std::map<std::string, std::string> report(const std::string& err, const std::string& label) {
    const std::string tag = "script report " + label + ": ";
    const auto at = err.find(tag);
    REQUIRE_MESSAGE(at != std::string::npos, "no report " << label);
    const auto end = err.find('\n', at);
    std::istringstream in(err.substr(at + tag.size(), end - at - tag.size()));
    std::map<std::string, std::string> kv;
    for (std::string w; in >> w;) {
        const auto eq = w.find('=');
        if (eq != std::string::npos) kv[w.substr(0, eq)] = w.substr(eq + 1);
    }
    return kv;
}

inline double num(const std::map<std::string, std::string>& kv, const std::string& key) {
    const auto it = kv.find(key);
    REQUIRE_MESSAGE(it != kv.end(), "report has no " << key);
    return std::strtod(it->second.c_str(), nullptr);
}

}  // namespace editor_test
