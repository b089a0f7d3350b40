// trial_profile.cpp — a simulated run's wall time by stage (trial_profile.hpp).
#include "engine/experiments/trial_profile.hpp"

#include <algorithm>
#include <cstdio>

namespace contactlab::experiments {
namespace {

thread_local TrialProfile* current = nullptr;

}  // namespace

TrialProfile& TrialProfile::operator+=(const TrialProfile& o) {
    stimulus += o.stimulus;
    servo_scene += o.servo_scene;
    device += o.device;
    tick += o.tick;
    records += o.records;
    platform += o.platform;
    perception += o.perception;
    files += o.files;
    wall += o.wall;
    virtual_s += o.virtual_s;
    trials += o.trials;
    return *this;
}

TrialProfile* thread_profile() { return current; }

ProfileScope::ProfileScope(TrialProfile* p) : previous_(current) { current = p; }
ProfileScope::~ProfileScope() { current = previous_; }

StageTimer::StageTimer(double TrialProfile::*stage) : profile_(current), stage_(stage) {
    if (profile_) start_ = std::chrono::steady_clock::now();
}

StageTimer::~StageTimer() {
    if (profile_) profile_->*stage_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string profile_table(const TrialProfile& p) {
    struct Row {
        const char* name;
        double s;
    };
    // The loops around the stages (plans, rows in memory, thread start); never below 0 (rounding).
    const double other = std::max(0.0, p.wall - p.staged());
    const Row rows[] = {{"servo tick", p.tick},
                        {"simulated rig (sim-cld)", p.device},
                        {"tick records", p.records},
                        {"servo scene and index", p.servo_scene},
                        {"stimulus and hand path", p.stimulus},
                        {"wearable platform (sim-wearable)", p.platform},
                        {"perception", p.perception},
                        {"files", p.files},
                        {"other (plans, results, threads)", other}};
    std::string out;
    char buf[160];
    std::snprintf(buf, sizeof buf, "profile: %llu trials, %.1f s of virtual time in %.2f s of wall time summed over the threads (%.0fx real time per thread)\n",
                  static_cast<unsigned long long>(p.trials), p.virtual_s, p.wall, p.wall > 0.0 ? p.virtual_s / p.wall : 0.0);
    out += buf;
    out += "| stage | ms per s of virtual time | share |\n| --- | ---: | ---: |\n";
    for (const Row& r : rows) {
        if (r.s == 0.0) continue;  // a stage this protocol does not have (the platform, the CLD rig)
        std::snprintf(buf, sizeof buf, "| %s | %.3f | %.1f %% |\n", r.name, p.virtual_s > 0.0 ? 1e3 * r.s / p.virtual_s : 0.0,
                      p.wall > 0.0 ? 100.0 * r.s / p.wall : 0.0);
        out += buf;
    }
    std::snprintf(buf, sizeof buf, "| all | %.3f | 100 %% |\n", p.virtual_s > 0.0 ? 1e3 * p.wall / p.virtual_s : 0.0);
    out += buf;
    return out;
}

}  // namespace contactlab::experiments
