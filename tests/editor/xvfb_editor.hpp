// xvfb_editor.hpp — runs the real `contactlab edit` under `xvfb-run -a` with lavapipe, and reads
// the `report LABEL` lines its scripts print (engine/editor/script.hpp), for the editor's tests.
#pragma once

#include "process.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace editor_test {

inline cli_test::ProcessResult run_under_xvfb(std::vector<std::string> args, const std::string& cwd = {}) {
    setenv("VK_DRIVER_FILES", "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json", 1);
    std::vector<std::string> all = {"-a", "-s", "-screen 0 1600x1000x24", cli_test::exe_path()};
    all.insert(all.end(), args.begin(), args.end());
    return cli_test::run_process("/usr/bin/xvfb-run", all, cwd, std::chrono::seconds(120));
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
