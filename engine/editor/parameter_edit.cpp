// parameter_edit.cpp — one validation path for every tunable parameter (parameter_edit.hpp).
#include "engine/editor/parameter_edit.hpp"

#include "engine/editor/experiment_mode.hpp"
#include "engine/editor/servo_view.hpp"
#include "haptics/scene_io.hpp"
#include "haptics/servo_params_check.hpp"

#include <cmath>
#include <cstdio>

namespace contactlab::editor {
namespace {

// Seed 004's eccentricity bound, as scene files have it (scene_io.cpp, force.eccentricity).
constexpr double kMaxEccentricity = 1e3;
constexpr double kMaxTravelMm = 1000.0;  // mm: a metre of roller travel is beyond any device

// What one edit would make of the editor's parameters.
struct Candidate {
    Scene scene;
    RollerGains roller;
    double travel = 0.0;  // m
    wearable::RigTuning wearable;
};

double eccentricity(const ForceLaw& law) { return law.k_normal / law.k_tangential; }
// Seed 004's total stiffness k (printed formula, force_law.hpp), N/m.
double total_stiffness(const ForceLaw& law) {
    return std::sqrt((law.k_tangential * law.k_tangential + 2.0 * law.k_normal * law.k_normal) / 3.0);
}

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// Writes `value` into the candidate. Returns a problem the limits cannot see (e.g. e <= 0 has no
// k_t to become), or "".
std::string apply(Candidate& c, std::string_view n, double v) {
    ForceDef& force = c.scene.force;
    ForceLaw& law = force.law;
    const bool ellipsoid = law.model == ForceModel::ellipsoid;
    if (n == "ke") {
        // The ellipsoid's "Ke" is its normal stiffness (scene_io reads it so): keep e.
        if (ellipsoid && v > 0.0) {
            const double e = eccentricity(law);
            law.k_normal = v;
            law.k_tangential = v / e;
        }
        force.stiffness = v;
    } else if (n == "max_force") {
        force.max_force = v;
    } else if (n == "damping") {
        law.damping = v;
    } else if (n == "mu_s") {
        law.mu_static = v;
    } else if (n == "mu_d") {
        law.mu_dynamic = v;
    } else if (n == "k_t") {
        law.k_tangential = v;
    } else if (n == "k_n") {
        law.k_normal = v;
        if (ellipsoid) force.stiffness = v;
    } else if (n == "eccentricity" || n == "total_k") {
        // Seed 004's (e, k) pair (eq. 3): the other one is kept as it is now.
        double e = eccentricity(law), k = total_stiffness(law);
        (n == "eccentricity" ? e : k) = v;
        if (!(e > 0.0 && e <= kMaxEccentricity))
            return "eccentricity: must lie in (0, " + fmt(kMaxEccentricity) + "], got " + fmt(e);
        if (!(k > 0.0)) return "total_k: must be > 0 N/m, got " + fmt(k);
        law.k_tangential = tangential_stiffness_from(k, e);
        law.k_normal = e * law.k_tangential;
        if (ellipsoid) force.stiffness = law.k_normal;
    } else if (n == "tolerance") {
        c.scene.curves.tolerance = v;
    } else if (n == "finger_r") {
        c.scene.finger.radius = v;
    } else if (n == "pad_l") {
        c.scene.finger.length = v;
    } else if (n == "kp") {
        c.roller.kp = v;
    } else if (n == "ki") {
        c.roller.ki = v;
    } else if (n == "kd") {
        c.roller.kd = v;
    } else if (n == "max_drive") {
        c.roller.max_drive = v;
    } else if (n == "roller_kff") {
        c.roller.kff = v;
    } else if (n == "ff_cutoff_hz") {
        c.roller.ff_cutoff_hz = v;
    } else if (n == "wearable_force_kp") {
        c.wearable.force_kp = v;
    } else if (n == "wearable_force_kd") {
        c.wearable.force_kd = v;
    } else if (n == "wearable_position_kp") {
        c.wearable.position_kp = v;
    } else if (n == "wearable_position_kd") {
        c.wearable.position_kd = v;
    } else if (n == "wearable_fit") {
        if (v != 0.0 && v != 1.0) return "wearable_fit: 1 (the seed's measured 45 ms response) or 0 (Table 1's motor alone), got " + fmt(v);
        c.wearable.seed_fit = v == 1.0;
    } else if (n == "fsr_noise") {
        c.wearable.fsr_noise = v;
    } else if (n == "travel_mm") {
        if (!(v >= 0.0 && v <= kMaxTravelMm))
            return "travel_mm: must lie in [0, " + fmt(kMaxTravelMm) + "] mm (0: the device's whole travel), got " + fmt(v);
        c.travel = v * 1e-3;  // m
    }
    return {};
}

// The shared limits: scene_io's rules for the scene's parameters (the contours are left out, so
// a half-drawn shape does not block a stiffness change), then the servo's own check of what
// would be published (stiffness range, roller gains, travel).
std::string check(const EditorState& s, const Candidate& c) {
    Scene params_only = c.scene;
    params_only.contours.clear();
    // The ellipsoid's stiffnesses are checked whatever the model: a spring scene keeps them for
    // the switch to the ellipsoid (set_force_model), so a refused k_t must not hide there.
    params_only.force.law.model = ForceModel::ellipsoid;
    try {
        validate_scene(params_only);
    } catch (const SceneError& e) {
        return e.what();
    }
    if (std::string p = roller_gains_problem(c.roller); !p.empty()) return p;
    if (std::string p = wearable::rig_tuning_problem(c.wearable); !p.empty()) return "wearable." + p;
    if (s.servo && s.haptics) {
        const ServoParams p = servo_params_for(c.scene, c.roller, s.haptics->watchdog_timeout(), c.travel);
        if (std::string problem = s.servo->params_problem(p); !problem.empty()) return problem;
    }
    return {};
}

const ParameterInfo* find(std::string_view name) {
    for (const ParameterInfo& p : tunable_parameters())
        if (name == p.name) return &p;
    return nullptr;
}

}  // namespace

const std::vector<ParameterInfo>& tunable_parameters() {
    static const std::vector<ParameterInfo> all = {
        {"ke", "N/m", "wall stiffness Ke (the ellipsoid's k_normal)", true},
        {"max_force", "N", "force limit", true},
        {"k_t", "N/m", "ellipsoid tangential stiffness", true},
        {"k_n", "N/m", "ellipsoid normal stiffness", true},
        {"eccentricity", "", "seed 004's e = k_n / k_t (total k kept)", true},
        {"total_k", "N/m", "seed 004's total stiffness k (e kept)", true},
        {"damping", "N s/m", "damping", true},
        {"mu_s", "", "static friction coefficient", true},
        {"mu_d", "", "dynamic friction coefficient", true},
        {"finger_r", "m", "finger radius R", true},
        {"pad_l", "m", "pad length L", true},
        {"tolerance", "m", "flatten mode's chord tolerance", true},
        {"kp", "V/m", "roller PID proportional gain", false},
        {"ki", "V/(m s)", "roller PID integral gain", false},
        {"kd", "V s/m", "roller PID derivative gain", false},
        {"max_drive", "V", "roller drive limit", false},
        {"roller_kff", "V s/m", "roller velocity feed-forward (0: seed 000's eq. 2 alone)", false},
        {"ff_cutoff_hz", "Hz", "cut-off of the feed-forward's target-rate filter", false},
        {"travel_mm", "mm", "usable roller travel (0: the device's whole)", false},
        {"wearable_force_kp", "N m/N", "wearable force loop K_p (seed 003 Fig. 5)", false},
        {"wearable_force_kd", "N m s/N", "wearable force loop K_d", false},
        {"wearable_position_kp", "N m/m", "wearable position loop K_p (seed 003 Fig. 6)", false},
        {"wearable_position_kd", "N m s/m", "wearable position loop K_d", false},
        {"wearable_fit", "", "1: the seed's measured 45 ms response, 0: Table 1's motor alone", false},
        {"fsr_noise", "N", "wearable FSR noise (standard deviation)", false},
    };
    return all;
}

bool is_tunable_parameter(std::string_view name) { return find(name) != nullptr; }

std::optional<double> parameter_value(const EditorState& s, std::string_view n) {
    const Scene& sc = s.doc.scene();
    const ForceLaw& law = sc.force.law;
    if (n == "ke") return sc.force.stiffness;
    if (n == "max_force") return sc.force.max_force;
    if (n == "damping") return law.damping;
    if (n == "mu_s") return law.mu_static;
    if (n == "mu_d") return law.mu_dynamic;
    if (n == "k_t") return law.k_tangential;
    if (n == "k_n") return law.k_normal;
    if (n == "eccentricity") return eccentricity(law);
    if (n == "total_k") return total_stiffness(law);
    if (n == "tolerance") return sc.curves.tolerance;
    if (n == "finger_r") return sc.finger.radius;
    if (n == "pad_l") return sc.finger.length;
    if (n == "kp") return s.roller.kp;
    if (n == "ki") return s.roller.ki;
    if (n == "kd") return s.roller.kd;
    if (n == "max_drive") return s.roller.max_drive;
    if (n == "travel_mm") return s.roller_travel * 1e3;
    if (n == "roller_kff") return s.roller.kff;
    if (n == "ff_cutoff_hz") return s.roller.ff_cutoff_hz;
    if (n == "wearable_force_kp") return s.wearable.force_kp;
    if (n == "wearable_force_kd") return s.wearable.force_kd;
    if (n == "wearable_position_kp") return s.wearable.position_kp;
    if (n == "wearable_position_kd") return s.wearable.position_kd;
    if (n == "wearable_fit") return s.wearable.seed_fit ? 1.0 : 0.0;
    if (n == "fsr_noise") return s.wearable.fsr_noise;
    return std::nullopt;
}

std::string parameter_problem(const EditorState& s, std::string_view name, double value) {
    if (!find(name)) return "unknown parameter \"" + std::string(name) + "\"";
    if (!std::isfinite(value)) return std::string(name) + ": must be a finite number";
    if (experiment_running(s))
        return std::string(name) + ": the trial's values are the protocol's while an experiment runs (Tuning shows them)";
    Candidate c{s.doc.scene(), s.roller, s.roller_travel, s.wearable};
    if (std::string p = apply(c, name, value); !p.empty()) return p;
    if (std::string p = check(s, c); !p.empty()) return std::string(name) + ": " + p;
    return {};
}

bool set_parameter(EditorState& s, std::string_view name, double value, EditKind kind) {
    if (std::string problem = parameter_problem(s, name, value); !problem.empty()) {
        s.say("refused " + problem, true);
        s.field_error_name = std::string(name);
        s.field_error = std::move(problem);
        return false;
    }
    Candidate c{s.doc.scene(), s.roller, s.roller_travel, s.wearable};
    apply(c, name, value);
    s.roller = c.roller;
    s.roller_travel = c.travel;
    s.wearable = c.wearable;
    const ParameterInfo& info = *find(name);
    if (info.in_scene) {
        if (kind == EditKind::drag_step) s.doc.update_continuous(std::move(c.scene));
        else s.doc.edit(std::move(c.scene), info.name);
    }
    s.field_error_name.clear();
    s.field_error.clear();
    s.say(std::string(info.name) + " = " + fmt(value) + (info.unit[0] ? " " : "") + info.unit);
    return true;
}

}  // namespace contactlab::editor
