// test_rooms.cpp — engine/experiments/ is a stack of rooms (engine/experiments/CMakeLists.txt,
// docs/ARCHITECTURE.md) and its includes run downward only: no room includes a room above it
// or beside it, no file includes one that includes it back (no circle), and neither
// engine/experiments/ nor engine/reports/ includes the app, the editor or the bench. The check
// reads the source tree itself, so a new include that runs back up fails here, naming the file.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// Floors, bottom up; rooms on one floor (procedures, participants) are siblings and must not
// include each other.
const std::map<std::string, int> kFloor = {
    {"base", 0},         {"protocol", 1}, {"procedures", 2}, {"participants", 2},
    {"runs", 3},         {"analysis", 4}, {"calibration", 5},
};

// Files by their path from the project root ("engine/experiments/runs/run_meta.cpp") to text.
using SourceTree = std::map<std::string, std::string>;

std::vector<std::string> quoted_includes(const std::string& text) {
    static const std::regex include_line(R"re(^\s*#\s*include\s*"([^"]+)")re");
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    std::smatch m;
    while (std::getline(in, line))
        if (std::regex_search(line, m, include_line)) out.push_back(m[1]);
    return out;
}

// "engine/experiments/ROOM/FILE" -> ROOM; "" for anything else.
std::string room_of(const std::string& path) {
    const std::string prefix = "engine/experiments/";
    if (path.rfind(prefix, 0) != 0) return "";
    const auto slash = path.find('/', prefix.size());
    return slash == std::string::npos ? "" : path.substr(prefix.size(), slash - prefix.size());
}

// "a/b/name.cpp" -> "a/b/name": a header and its source are one node of the include graph.
std::string module_of(const std::string& path) { return path.substr(0, path.rfind('.')); }

// Every rule broken, one line each ("FILE includes X: why"); empty when the tree keeps them all.
std::vector<std::string> room_violations(const SourceTree& tree) {
    std::vector<std::string> bad;
    std::map<std::string, std::set<std::string>> arrows;  // module -> modules it includes
    for (const auto& [path, text] : tree) {
        const bool in_experiments = path.rfind("engine/experiments/", 0) == 0;
        const bool in_reports = path.rfind("engine/reports/", 0) == 0;
        if (!in_experiments && !in_reports) continue;
        const std::string room = room_of(path);
        if (in_experiments && !kFloor.count(room)) {
            bad.push_back(path + ": not inside one of the rooms (base, protocol, procedures, participants, runs, analysis, calibration)");
            continue;
        }
        for (const std::string& inc : quoted_includes(text)) {
            for (const char* above : {"engine/app/", "engine/editor/", "engine/bench/"})
                if (inc.rfind(above, 0) == 0) bad.push_back(path + " includes " + inc + ": " + above + " is above it");
            if (in_experiments && (inc.rfind("engine/reports/", 0) == 0 || inc.rfind("engine/render/", 0) == 0))
                bad.push_back(path + " includes " + inc + ": the experiments know nothing of reports or rendering");
            if (inc.rfind("engine/experiments/", 0) != 0) continue;
            const std::string to = room_of(inc);
            if (!kFloor.count(to)) {
                bad.push_back(path + " includes " + inc + ": not a room's file");
                continue;
            }
            if (!tree.count(inc)) bad.push_back(path + " includes " + inc + ": no such file");
            if (in_experiments && to != room && kFloor.at(to) >= kFloor.at(room))
                bad.push_back(path + " includes " + inc + ": room " + to + " is not below room " + room);
            if (in_experiments && module_of(inc) != module_of(path)) arrows[module_of(path)].insert(module_of(inc));
        }
    }
    // A circle among the files (a header and its source as one): depth-first, grey = on the path.
    std::map<std::string, int> colour;
    std::vector<std::string> path_now;
    std::function<void(const std::string&)> visit = [&](const std::string& m) {
        colour[m] = 1;
        path_now.push_back(m);
        for (const std::string& next : arrows[m]) {
            if (colour[next] == 1) {
                std::string circle;
                for (auto it = std::find(path_now.begin(), path_now.end(), next); it != path_now.end(); ++it) circle += *it + " -> ";
                bad.push_back("a circle of includes: " + circle + next);
            } else if (colour[next] == 0) {
                visit(next);
            }
        }
        path_now.pop_back();
        colour[m] = 2;
    };
    for (const auto& [m, unused] : arrows)
        if (colour[m] == 0) visit(m);
    return bad;
}

SourceTree read_tree(const fs::path& root) {
    SourceTree tree;
    for (const char* dir : {"engine/experiments", "engine/reports"}) {
        for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
            const std::string ext = e.path().extension().string();
            if (!e.is_regular_file() || (ext != ".hpp" && ext != ".cpp")) continue;
            std::ifstream in(e.path());
            std::ostringstream text;
            text << in.rdbuf();
            tree[fs::relative(e.path(), root).generic_string()] = text.str();
        }
    }
    return tree;
}

std::string joined(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += x + "\n";
    return s;
}

}  // namespace

TEST_CASE("rooms: the checker finds an include that runs back up, a sibling's, a circle and a stray file") {
    SourceTree t = {
        {"engine/experiments/base/a.hpp", ""},
        {"engine/experiments/protocol/p.hpp", "#include \"engine/experiments/base/a.hpp\"\n"},
        {"engine/experiments/runs/r.hpp", "#include \"engine/experiments/protocol/p.hpp\"\n"},
    };
    CHECK(room_violations(t).empty());

    SourceTree up = t;
    up["engine/experiments/runs/q.hpp"] = "";
    up["engine/experiments/protocol/p.cpp"] = "#include \"engine/experiments/runs/q.hpp\"\n";
    const auto up_bad = room_violations(up);
    REQUIRE(up_bad.size() == 1);
    CHECK(up_bad[0].find("room runs is not below room protocol") != std::string::npos);

    SourceTree sibling = t;
    sibling["engine/experiments/procedures/s.hpp"] = "";
    sibling["engine/experiments/participants/q.cpp"] = "#include \"engine/experiments/procedures/s.hpp\"\n";
    CHECK(room_violations(sibling).size() == 1);

    SourceTree circle = t;
    circle["engine/experiments/base/b.hpp"] = "#include \"engine/experiments/base/c.hpp\"\n";
    circle["engine/experiments/base/c.cpp"] = "#include \"engine/experiments/base/b.hpp\"\n";
    circle["engine/experiments/base/c.hpp"] = "";
    const auto circle_bad = room_violations(circle);
    REQUIRE(circle_bad.size() == 1);
    CHECK(circle_bad[0].find("a circle of includes") != std::string::npos);

    SourceTree stray = t;
    stray["engine/experiments/loose.cpp"] = "";
    stray["engine/reports/fig.cpp"] = "#include \"engine/app/command_line.hpp\"\n";
    CHECK(room_violations(stray).size() == 2);
}

TEST_CASE("rooms: engine/experiments/ and engine/reports/ include downward only, with no circle") {
    const SourceTree tree = read_tree(CONTACTLAB_SOURCE_DIR);
    // Every room holds files (a renamed or emptied room is a change to this test and the docs).
    for (const auto& [room, floor] : kFloor) {
        bool found = false;
        for (const auto& [path, text] : tree) found = found || room_of(path) == room;
        CHECK_MESSAGE(found, "room " << room << " has no files");
    }
    CHECK(tree.size() > 60);
    const auto bad = room_violations(tree);
    CHECK_MESSAGE(bad.empty(), joined(bad));
}
