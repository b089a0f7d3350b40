// rig_tuning.cpp — the wearable rig's live parameters (see rig_tuning.hpp).
#include "haptics/wearable/rig_tuning.hpp"

#include <cmath>
#include <cstdio>

namespace contactlab::wearable {
namespace {

std::string gain_problem(const char* name, double v, const char* unit) {
    if (std::isfinite(v) && v >= 0.0) return {};
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s: must be a finite number >= 0 %s, got %.6g", name, unit, v);
    return buf;
}

}  // namespace

double seed_fit_time_constant() { return seed_fit_rig().reference_time_constant; }

RigTuning tuning_of(const RigDef& def) {
    RigTuning t;
    t.force_kp = def.force.kp;
    t.force_kd = def.force.kd;
    t.position_kp = def.position.kp;
    t.position_kd = def.position.kd;
    t.seed_fit = def.reference_time_constant > 0.0;
    t.fsr_noise = def.plant.fsr_noise;
    return t;
}

void apply_tuning(RigDef& def, const RigTuning& t) {
    def.force.kp = t.force_kp;
    def.force.kd = t.force_kd;
    def.position.kp = t.position_kp;
    def.position.kd = t.position_kd;
    def.reference_time_constant = t.seed_fit ? seed_fit_time_constant() : 0.0;
    def.plant.fsr_noise = t.fsr_noise;
}

std::string rig_tuning_problem(const RigTuning& t) {
    for (const std::string& p : {gain_problem("force_kp", t.force_kp, "N m/N"), gain_problem("force_kd", t.force_kd, "N m s/N"),
                                  gain_problem("position_kp", t.position_kp, "N m/m"),
                                  gain_problem("position_kd", t.position_kd, "N m s/m")})
        if (!p.empty()) return p;
    if (!(std::isfinite(t.fsr_noise) && t.fsr_noise >= 0.0 && t.fsr_noise <= kMaxFsrNoise)) {
        char buf[120];
        std::snprintf(buf, sizeof buf, "fsr_noise: must lie in [0, %g] N, got %.6g", kMaxFsrNoise, t.fsr_noise);
        return buf;
    }
    return {};
}

void WearableRig::retune(const RigTuning& t) {
    apply_tuning(def_, t);
    plant_.set_fsr_noise(t.fsr_noise);
    // Fresh controllers with the new gains: their derivative filters restart (as at a mode switch),
    // so a gain change never multiplies a rate filtered under the old one.
    force_ = ForceController(def_.force, def_.plant.motor);
    position_ = PositionController(def_.position, def_.plant.motor, def_.plant.platform, def_.estimator.slack_tension);
}

}  // namespace contactlab::wearable
