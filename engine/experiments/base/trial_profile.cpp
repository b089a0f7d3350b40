// trial_profile.cpp — a simulated run's wall time by stage (trial_profile.hpp).
#include "engine/experiments/base/trial_profile.hpp"

#include <algorithm>
#include <cstdio>

namespace contactlab::experiments {
namespace {

thread_local TrialProfile* current = nullptr;

}  // namespace

double TrialProfile::staged() const {
    double sum = 0.0;
    for (const ProfileStage& st : kProfileStages) sum += this->*st.field;
    return sum;
}

TrialProfile& TrialProfile::operator+=(const TrialProfile& o) {
    for (const ProfileStage& st : kProfileStages) this->*st.field += o.*st.field;
    wall += o.wall;
    virtual_s += o.virtual_s;
    trials += o.trials;
    return *this;
}

TrialProfile* thread_profile() { return current; }

ProfileScope::ProfileScope(TrialProfile* p) : previous_(current) { current = p; }
ProfileScope::~ProfileScope() { current = previous_; }

StageTimer::StageTimer(double TrialProfile::*stage) : profile_(current), stage_(stage) { clock_.start(profile_ != nullptr); }

StageTimer::~StageTimer() {
    if (!profile_) return;
    double ns = 0.0;
    clock_.lap(ns);
    profile_->*stage_ += ns * 1e-9;
}

std::string profile_table(const TrialProfile& p) {
    std::string out;
    char buf[160];
    std::snprintf(buf, sizeof buf, "profile: %llu trials, %.1f s of virtual time in %.2f s of wall time summed over the threads (%.0fx real time per thread)\n",
                  static_cast<unsigned long long>(p.trials), p.virtual_s, p.wall, p.wall > 0.0 ? p.virtual_s / p.wall : 0.0);
    out += buf;
    out += "| stage | ms per s of virtual time | share |\n| --- | ---: | ---: |\n";
    auto row = [&](const char* label, double s) {
        if (s == 0.0) return;  // a stage this protocol does not have (the platform, the CLD rig)
        std::snprintf(buf, sizeof buf, "| %s | %.3f | %.1f %% |\n", label, p.virtual_s > 0.0 ? 1e3 * s / p.virtual_s : 0.0,
                      p.wall > 0.0 ? 100.0 * s / p.wall : 0.0);
        out += buf;
    };
    for (const ProfileStage& st : kProfileStages) row(st.label, p.*st.field);
    // The loops around the stages (plans, rows in memory, thread start); never below 0 (rounding).
    row("other (plans, results, threads)", std::max(0.0, p.wall - p.staged()));
    std::snprintf(buf, sizeof buf, "| all | %.3f | 100 %% |\n", p.virtual_s > 0.0 ? 1e3 * p.wall / p.virtual_s : 0.0);
    out += buf;
    return out;
}

}  // namespace contactlab::experiments
