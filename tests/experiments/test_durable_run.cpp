// test_durable_run.cpp — `contactlab experiment run` keeps what it did: killed for real (SIGKILL
// once some rows are on disk) and started again with the same command, it ends with the bytes an
// uninterrupted run writes, with --jobs 1 and 2; it leaves no temporary file; it refuses to run
// into another run's files unless --overwrite, which clears their traces; a finished run is not
// run again.
#include "process.hpp"

#include <nlohmann/json.hpp>

#include <doctest/doctest.h>

#include <filesystem>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>
#include <sstream>
#include <string>

using namespace cli_test;

namespace {

// Seed 002's task, small: 2 conditions x 8 trials (1 warm-up) per participant, a few seconds.
std::string small_protocol(const TempDir& dir, int trials = 8) {
    std::string text = read_text((source_dir() / "scenes/experiments/002-bump-counting.json").string());
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"\"trials\": 135", "\"trials\": " + std::to_string(trials)},
                                   std::pair<std::string, std::string>{"\"warmup\": 10", "\"warmup\": 1"}}) {
        const auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    }
    const std::string path = dir.file("small-002.json");
    write_text(path, text);
    return path;
}

// Rows (lines less the header) of a CSV file, 0 when it is not there.
std::size_t rows_in(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return 0;
    std::string text;
    try {
        text = read_text(path);
    } catch (...) {
        return 0;
    }
    const auto n = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    return n > 0 ? n - 1 : 0;
}

// Starts `contactlab args...` and kills it (SIGKILL, by its pid) once `ready` says so; returns
// false when it exited by itself first.
template <class Ready>
bool kill_when(const std::vector<std::string>& args, Ready ready) {
    const pid_t pid = start_process(exe_path(), args);
    int status = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        if (::waitpid(pid, &status, WNOHANG) == pid) return false;
        if (ready()) {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            return true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    return false;
}

// Every file below `dir` whose name looks like write_file_atomically's temporary.
std::vector<std::string> temporaries(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string().find(".tmp-") != std::string::npos) out.push_back(e.path().string());
    return out;
}

void check_same_traces(const std::string& a, const std::string& b) {
    std::vector<std::string> na, nb;
    for (const auto& e : fs::directory_iterator(a)) na.push_back(e.path().filename().string());
    for (const auto& e : fs::directory_iterator(b)) nb.push_back(e.path().filename().string());
    std::sort(na.begin(), na.end());
    std::sort(nb.begin(), nb.end());
    REQUIRE(na == nb);
    for (const std::string& n : na) CHECK(read_text(a + "/" + n) == read_text(b + "/" + n));
}

void killed_and_resumed(int jobs) {
    TempDir dir;
    const std::string proto = small_protocol(dir);
    auto args = [&](const std::string& out) {
        return std::vector<std::string>{"experiment", "run", proto, "--participants", "sim:1-2", "--seed", "4",
                                        "--jobs", std::to_string(jobs), "-o", out};
    };
    const auto whole = run_contactlab(args(dir.file("whole.csv")));
    INFO("stderr: " << whole.err);
    REQUIRE(whole.exit_code == 0);
    CHECK(rows_in(dir.file("whole.csv")) == 2 * 2 * 8);

    // Killed once participant 1 has 5 trials on disk (of 16): mid-block, mid-run.
    const std::string out = dir.file("r.csv");
    REQUIRE(kill_when(args(out), [&] { return rows_in(out + ".parts/sim1.csv") >= 5; }));
    CHECK(rows_in(out + ".parts/sim1.csv") < 16);
    CHECK(nlohmann::json::parse(read_text(out + ".meta.json"))["finished_utc"].is_null());
    // What a kill inside write_file_atomically leaves: temporaries beside their targets.
    write_text(out + ".tmp-Ab12Cd", "half");
    write_text(out + ".parts/sim1.csv.tmp-Ab12Cd", "half");
    write_text(out + ".traces/sim1-F-1.csv.tmp-Ab12Cd", "half");

    const auto again = run_contactlab(args(out));
    INFO("stderr: " << again.err);
    REQUIRE(again.exit_code == 0);
    CHECK(contains(again.err, "resumed"));
    CHECK(read_text(out) == read_text(dir.file("whole.csv")));
    check_same_traces(out + ".traces", dir.file("whole.csv.traces"));
    CHECK(temporaries(dir.path()).empty());
    CHECK_FALSE(fs::exists(out + ".parts"));
    const auto meta = nlohmann::json::parse(read_text(out + ".meta.json"));
    CHECK(meta["finished_utc"].is_string());
    CHECK(meta["rows"] == 32);
    CHECK(meta["resumed"].size() == 1);
    // The killed run's lock file was taken over and removed when the run finished.
    CHECK_FALSE(fs::exists(out + ".lock"));
    CHECK_FALSE(fs::exists(dir.file("whole.csv.lock")));
}

// Holds OUT.lock as a live run does (flock), until it goes away.
class HeldLock {
public:
    explicit HeldLock(const std::string& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
        REQUIRE(fd_ >= 0);
        REQUIRE(::flock(fd_, LOCK_EX | LOCK_NB) == 0);
    }
    ~HeldLock() { ::close(fd_); }
    HeldLock(const HeldLock&) = delete;
    HeldLock& operator=(const HeldLock&) = delete;

private:
    int fd_;
};

}  // namespace

TEST_CASE("experiment run: a batch killed with SIGKILL and run again ends with the uninterrupted run's bytes") {
    killed_and_resumed(1);
}

TEST_CASE("experiment run: killed and resumed with --jobs 2, the same bytes as an uninterrupted run") {
    killed_and_resumed(2);
}

TEST_CASE("experiment run: another protocol's, seed's or participants' file is refused unless --overwrite") {
    TempDir dir;
    const std::string proto = small_protocol(dir, 4), other = dir.file("other.json");
    write_text(other, read_text(proto) + "\n");  // the same protocol but for a byte: another sha256
    const std::string out = dir.file("r.csv");
    const std::vector<std::string> base = {"experiment", "run", proto, "--participant", "sim", "-o", out};
    REQUIRE(run_contactlab(base).exit_code == 0);
    const std::string first = read_text(out);

    // The same run again: complete, nothing is run or rewritten.
    const auto same = run_contactlab(base);
    CHECK(same.exit_code == 0);
    CHECK(contains(same.err, "nothing to do"));
    CHECK(read_text(out) == first);

    const auto p = run_contactlab({"experiment", "run", other, "--participant", "sim", "-o", out});
    CHECK(p.exit_code == 2);
    CHECK(contains(p.err, "r.csv: written by another run: another protocol"));
    CHECK(contains(p.err, "--overwrite"));
    const auto s = run_contactlab({"experiment", "run", proto, "--participant", "sim", "--seed", "9", "-o", out});
    CHECK(s.exit_code == 2);
    CHECK(contains(s.err, "another seed"));
    const auto q = run_contactlab({"experiment", "run", proto, "--participants", "sim:1-2", "-o", out});
    CHECK(q.exit_code == 2);
    CHECK(contains(q.err, "other participants"));
    CHECK(read_text(out) == first);  // refused: untouched

    // --overwrite: the other protocol's run replaces it, and the old traces go with it.
    write_text(out + ".traces/stale.csv", "old run");
    const auto o = run_contactlab({"experiment", "run", other, "--participant", "sim", "-o", out, "--overwrite"});
    INFO("stderr: " << o.err);
    REQUIRE(o.exit_code == 0);
    CHECK_FALSE(fs::exists(out + ".traces/stale.csv"));
    CHECK(fs::exists(out + ".traces/sim1-F-1.csv"));
    CHECK(temporaries(dir.path()).empty());

    // A results file without a meta (an older ContactLab's, or another program's) is refused too.
    write_text(dir.file("old.csv"), "participant,condition\nsim1,F\n");
    const auto old = run_contactlab({"experiment", "run", proto, "--participant", "sim", "-o", dir.file("old.csv")});
    CHECK(old.exit_code == 2);
    CHECK(contains(old.err, "old.csv: exists without old.csv.meta.json"));
    CHECK(read_text(dir.file("old.csv")) == "participant,condition\nsim1,F\n");
}

TEST_CASE("experiment run: the meta names version, protocol (its sha256 as sha256sum computes it), seed, device, rate, times") {
    TempDir dir;
    const std::string proto = small_protocol(dir, 3), out = dir.file("r.csv");
    const auto p = run_contactlab({"experiment", "run", proto, "--participants", "sim:1-2", "--seed", "7", "-o", out, "--no-traces"});
    INFO("stderr: " << p.err);
    REQUIRE(p.exit_code == 0);
    const auto m = nlohmann::json::parse(read_text(out + ".meta.json"));
    for (const char* key : {"contactlab_version", "protocol_sha256", "protocol", "protocol_path", "seed", "participants", "device",
                            "servo_rate_hz", "started_utc", "finished_utc", "command"})
        CHECK_MESSAGE(m.contains(key), key);
    // An independent SHA-256 of the protocol file's bytes.
    const auto sum = run_process("/usr/bin/sha256sum", {proto});
    REQUIRE(sum.exit_code == 0);
    CHECK(m["protocol_sha256"] == sum.out.substr(0, 64));
    CHECK(m["protocol"]["task"] == "bump-counting");
    CHECK(m["protocol_path"] == proto);
    CHECK(m["seed"] == 7);
    CHECK(m["participants"] == nlohmann::json::array({"sim1", "sim2"}));
    CHECK(m["device"] == "sim-cld");
    CHECK(m["servo_rate_hz"] == 1000.0);
    CHECK(m["started_utc"].get<std::string>().size() == 20);  // 2025-01-31T12:00:00Z
    CHECK(m["finished_utc"].get<std::string>() >= m["started_utc"].get<std::string>());
    CHECK(contains(m["command"].get<std::string>(), "experiment run " + proto + " --participants sim:1-2 --seed 7"));
    CHECK_FALSE(fs::exists(out + ".traces"));

    // Each row: the stimulus's unit, the device, whether the finger touched, seed 002's bumps.
    const std::string csv = read_text(out);
    CHECK(csv.rfind("participant,condition,trial,stimulus,stimulus_unit,response,correct,valid,warmup,time_s,failed,"
                    "contact_breaks,contact_fraction,peak_force_n,touched,contact_location,device,small_bumps,large_bumps\n", 0) == 0);
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);
    int rows = 0;
    while (std::getline(lines, line)) {
        ++rows;
        CHECK(contains(line, ",bumps,"));
        CHECK(contains(line, ",1,1,sim-cld,") != contains(line, ",1,0,sim-cld,"));  // touched 1, either condition
    }
    CHECK(rows == 2 * 2 * 3);
}

TEST_CASE("experiment run: an adaptive run killed with SIGKILL resumes by replaying the stored answers, the same bytes as an uninterrupted run") {
    // The edge protocol's staircases, short (at most 20 trials per condition): the next
    // stimulus depends on the answers, so a resume that did not replay them would present
    // other stimuli and write other bytes (or be refused for a mismatched row).
    TempDir dir;
    nlohmann::json proto = nlohmann::json::parse(read_text((source_dir() / "scenes/experiments/edge-sharpness.json").string()));
    proto["procedure"]["max_trials"] = 20;
    proto["procedure"]["reversals"] = 6;
    proto["procedure"]["estimate_reversals"] = 4;
    const std::string path = dir.file("short-edge.json");
    write_text(path, proto.dump(2));
    auto args = [&](const std::string& out) {
        return std::vector<std::string>{"experiment", "run", path, "--participants", "sim:1-2", "--seed", "9", "--jobs", "1", "-o", out};
    };
    const auto whole = run_contactlab(args(dir.file("whole.csv")));
    INFO("stderr: " << whole.err);
    REQUIRE(whole.exit_code == 0);
    const std::string out = dir.file("r.csv");
    REQUIRE(kill_when(args(out), [&] { return rows_in(out + ".parts/sim1.csv") >= 9; }));
    CHECK(rows_in(out + ".parts/sim1.csv") < rows_in(dir.file("whole.csv")) / 2);
    const auto again = run_contactlab(args(out));
    INFO("stderr: " << again.err);
    REQUIRE(again.exit_code == 0);
    CHECK(contains(again.err, "resumed"));
    CHECK(read_text(out) == read_text(dir.file("whole.csv")));
    check_same_traces(out + ".traces", dir.file("whole.csv.traces"));
    // A stored answer changed: the replayed staircase goes elsewhere, and the run is refused
    // rather than continued from a state the file does not describe.
    const std::string out2 = dir.file("tampered.csv");
    REQUIRE(kill_when(args(out2), [&] { return rows_in(out2 + ".parts/sim1.csv") >= 9; }));
    std::string part = read_text(out2 + ".parts/sim1.csv");
    // Flip every stored answer's `correct` cell after the practice: ",first,1," <-> ",first,0,".
    std::string flipped;
    for (std::size_t i = 0; i < part.size(); ++i) {
        flipped += part[i];
        if ((part.compare(i, 7, ",first,") == 0 || part.compare(i, 8, ",second,") == 0)) {
            const std::size_t cell = part.find(',', i + 1) + 1;
            flipped += part.substr(i + 1, cell - i - 1);
            flipped += part[cell] == '1' ? '0' : '1';
            i = cell;
        }
    }
    write_text(out2 + ".parts/sim1.csv", flipped);
    const auto refused = run_contactlab(args(out2));
    CHECK(refused.exit_code == 2);
    // The first flipped answer no longer grades as its stimulus and response say.
    CHECK(contains(refused.err, "grades"));
}

TEST_CASE("issue 49: a run into a live run's output is told it is locked, even when the parts folder has no meta yet") {
    TempDir dir;
    const std::string proto = small_protocol(dir, 3), out = dir.file("r.csv");
    const std::vector<std::string> args = {"experiment", "run", proto, "--participant", "sim", "--no-traces", "-o", out};
    // The moment two runs start together: the first has locked and made its parts folder, and has
    // not yet written its meta. The second used to look at the folder first and be told it "exists
    // without r.csv.meta.json ... give --overwrite".
    fs::create_directories(out + ".parts");
    {
        const HeldLock live(out + ".lock");
        const auto p = run_contactlab(args);
        INFO("stderr: " << p.err);
        CHECK(p.exit_code == 2);
        CHECK(contains(p.err, "r.csv: another contactlab run is writing it now (" + out + ".lock is locked)"));
        CHECK_FALSE(contains(p.err, "exists without"));
        // --overwrite waits its turn too: the live run's folder is not removed under it.
        write_text(out + ".parts/sim1.csv", "the live run's rows");
        const auto o = run_contactlab({"experiment", "run", proto, "--participant", "sim", "--no-traces", "-o", out, "--overwrite"});
        CHECK(o.exit_code == 2);
        CHECK(contains(o.err, "is locked"));
        CHECK(read_text(out + ".parts/sim1.csv") == "the live run's rows");
        CHECK_FALSE(fs::exists(out + ".meta.json"));
    }
    // Unlocked, the same folder says what it is: parts without a meta.
    const auto q = run_contactlab(args);
    CHECK(q.exit_code == 2);
    CHECK(contains(q.err, "exists without r.csv.meta.json"));
    // And a run that finishes leaves no lock file behind.
    const auto r = run_contactlab({"experiment", "run", proto, "--participant", "sim", "--no-traces", "-o", dir.file("fresh/r.csv")});
    INFO("stderr: " << r.err);
    CHECK(r.exit_code == 0);
    CHECK(fs::exists(dir.file("fresh/r.csv")));
    CHECK_FALSE(fs::exists(dir.file("fresh/r.csv.lock")));
    const auto again = run_contactlab({"experiment", "run", proto, "--participant", "sim", "--no-traces", "-o", dir.file("fresh/r.csv")});
    CHECK(contains(again.err, "nothing to do"));
    CHECK_FALSE(fs::exists(dir.file("fresh/r.csv.lock")));
}

// Issue 49: a run folder is verified before it is resumed. Each committed row and its trace have
// their SHA-256 in RESULTS.csv.parts/P.sums; a resume checks every row it replays against it, and
// its `correct` against its stimulus and response, and refuses (exit 2, naming the file and the
// trial) instead of carrying on from a folder the run did not write.
TEST_CASE("issue 49: a resume refuses a changed digit, a flipped correct, and a deleted trace, naming the file and trial") {
    TempDir dir;
    const std::string proto = small_protocol(dir);
    auto args = [&](const std::string& out) {
        return std::vector<std::string>{"experiment", "run", proto, "--participants", "sim:1-2", "--seed", "4", "--jobs", "1", "-o", out};
    };
    // The part's rows as cells (header first).
    auto cells = [](const std::string& text) {
        std::vector<std::vector<std::string>> rows;
        std::stringstream lines(text);
        for (std::string line; std::getline(lines, line);) {
            std::vector<std::string> r;
            std::stringstream fields(line);
            for (std::string f; std::getline(fields, f, ',');) r.push_back(f);
            rows.push_back(r);
        }
        return rows;
    };
    auto join = [](const std::vector<std::vector<std::string>>& rows) {
        std::string text;
        for (const auto& r : rows) {
            for (std::size_t i = 0; i < r.size(); ++i) text += (i ? "," : "") + r[i];
            text += "\n";
        }
        return text;
    };
    struct Case {
        const char* name;
        const char* says;
    };
    for (const Case c : {Case{"digit", "SHA-256 differs"}, Case{"correct", "grades"}, Case{"trace", "missing"}}) {
        CAPTURE(c.name);
        const std::string out = dir.file(std::string(c.name) + ".csv");
        REQUIRE(kill_when(args(out), [&] { return rows_in(out + ".parts/sim1.csv") >= 4; }));
        const std::string part = out + ".parts/sim1.csv";
        REQUIRE(fs::exists(out + ".parts/sim1.sums"));
        auto rows = cells(read_text(part));
        REQUIRE(rows.size() >= 5);
        const std::size_t col_correct = 6, col_peak = 13;
        REQUIRE(rows[0][col_correct] == "correct");
        REQUIRE(rows[0][col_peak] == "peak_force_n");
        if (std::string(c.name) == "digit") {
            char& d = rows[2][col_peak].back();  // one digit of row 2's peak force
            d = d == '9' ? '8' : static_cast<char>(d + 1);
            write_text(part, join(rows));
        } else if (std::string(c.name) == "correct") {
            rows[3][col_correct] = rows[3][col_correct] == "1" ? "0" : "1";
            write_text(part, join(rows));
        } else {
            fs::remove(out + ".traces/sim1-" + rows[1][1] + "-" + rows[1][2] + ".csv");
        }
        const auto again = run_contactlab(args(out));
        CAPTURE(again.err);
        CHECK(again.exit_code == 2);
        CHECK(contains(again.err, c.says));
        CHECK(contains(again.err, std::string(c.name) == "trace" ? "sim1-" : "parts/sim1.csv: row "));
        CHECK(contains(again.err, "--overwrite"));
        CHECK_FALSE(nlohmann::json::parse(read_text(out + ".meta.json"))["finished_utc"].is_string());
    }
}
