// simulate_wearable.cpp — seed 003's experiments for `contactlab simulate` (see simulate_wearable.hpp).
#include "engine/app/simulate_wearable.hpp"
#include "engine/app/subcommands.hpp"

#include "drivers/sim/wearable_tasks.hpp"
#include "haptics/scene_io.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <variant>

namespace contactlab::app {

using namespace contactlab::drivers::sim;
using namespace contactlab::wearable;

bool is_wearable_task(const std::string& task) {
    return task == "wearable-step" || task == "wearable-bandwidth" || task == "curvature-arc";
}

namespace {

void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path);
    if (!out) throw BadInput("cannot write " + path);
    out << text;
    out.close();
    if (!out) throw BadInput("cannot write " + path);
}

std::string fmt(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

std::string samples_csv(const std::vector<WearableSample>& samples) {
    std::string s = "t,Q_r,Qhat_1,Qhat_2,Qhat_3,Q_1,Q_2,Q_3,fault\n";  // s, N x7
    char line[256];
    for (const WearableSample& w : samples) {
        std::snprintf(line, sizeof line, "%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%d\n", w.t, w.reference(0), w.estimate(0),
                      w.estimate(1), w.estimate(2), w.tension(0), w.tension(1), w.tension(2), w.fault ? 1 : 0);
        s += line;
    }
    return s;
}

// Chord and height (m) of the scene's first circular arc: the bump of `contactlab generate arc`.
void arc_of(const Scene& scene, double& chord, double& height) {
    for (const Contour& c : scene.contours) {
        for (const Segment& seg : c.segments) {
            if (const auto* a = std::get_if<ArcSegment>(&seg)) {
                const Vec2 p0 = a->center + a->radius * Vec2{std::cos(a->start_angle), std::sin(a->start_angle)};
                const Vec2 p1 = a->center + a->radius * Vec2{std::cos(a->end_angle), std::sin(a->end_angle)};
                chord = glm::length(p1 - p0);
                const double half = 0.5 * chord;
                height = a->radius - std::sqrt(std::max(0.0, a->radius * a->radius - half * half));
                return;
            }
        }
    }
    throw BadInput("--task curvature-arc: the scene has no circular arc (make one with: contactlab generate arc "
                   "--chord 0.30 --height 0.02 --output arc.json)");
}

}  // namespace

int run_wearable_task(const SimulateOptions& o) {
    if (o.device != "sim-wearable" && o.device != "sim-cld")
        throw BadInput("--task " + o.task + " runs on the simulated wearable platform (--device sim-wearable)");
    if (!o.hand.empty()) throw BadInput("--task " + o.task + " takes no --hand");
    if (o.realtime) throw BadInput("--task " + o.task + " runs in virtual time only");
    if (!o.record.empty()) throw BadInput("--task " + o.task + " records nothing (no --record)");
    if (o.wearable_fit != "seed" && o.wearable_fit != "none")
        throw BadInput("--wearable-fit: seed (the seed's measured 45 ms response) or none (Table 1's motor alone)");
    const Scene scene = load_scene_file(o.scene_path);
    RigDef def = o.wearable_fit == "seed" ? seed_fit_rig() : RigDef{};
    def.force.rate_hz = o.rate;
    def.position.rate_hz = o.rate;
    def.plant.fsr_noise = o.fsr_noise;
    if (scene.wearable.has_finger_stiffness) {  // the scene's K (scenes/README.md, "wearable")
        const Mat6 k = Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(scene.wearable.finger_stiffness.data());
        const StiffnessCheck sc = check_stiffness(k);
        if (!sc.ok) throw BadInput(o.scene_path + ": wearable.finger_stiffness: " + sc.why);
        def.plant.stiffness = k;
    }
    if (!(std::isfinite(o.fsr_noise) && o.fsr_noise >= 0.0 && o.fsr_noise <= 0.1))
        throw BadInput("--fsr-noise: must be in [0, 0.1] N");
    std::string json = "{\n  \"task\": \"" + o.task + "\",\n  \"device\": \"sim-wearable\",\n";
    json += "  \"rate_hz\": " + fmt("%.6g", o.rate) + ",\n  \"command_rate_hz\": " + fmt("%.6g", def.force.command_rate_hz) + ",\n";
    json += "  \"reference_time_constant_s\": " + fmt("%.6g", def.reference_time_constant) + ",\n";
    json += "  \"fsr_noise_n\": " + fmt("%.6g", o.fsr_noise) + ",\n";
    json += std::string("  \"finger_stiffness\": \"") + (scene.wearable.has_finger_stiffness ? "scene" : "seed k I (mm)") + "\",\n";
    if (o.task == "wearable-step") {
        const WearableStepResult r = wearable_step(def);
        write_file(o.output, samples_csv(r.samples));
        json += "  \"step_n\": 0.3,\n  \"rise_time_s\": " + fmt("%.6g", r.rise_time_s) + ",\n  \"steady_error_pct\": " +
                fmt("%.6g", r.steady_error_pct) + ",\n  \"overshoot_pct\": " + fmt("%.6g", r.overshoot_pct) +
                ",\n  \"fault\": " + (r.fault ? "true" : "false") + ",\n  \"seed\": {\"rise_time_s\": 0.1, \"steady_error_pct_below\": 2}\n}\n";
        std::fprintf(stderr, "simulate: wearable 0.3 N step: rise (10-90 %%) %.3f s, steady error %.2f %%, overshoot %.1f %% "
                     "(seed 003: about 0.1 s, < 2 %%)%s\n", r.rise_time_s, r.steady_error_pct, r.overshoot_pct,
                     r.fault ? "; a fault occurred" : "");
    } else if (o.task == "wearable-bandwidth") {
        std::vector<WearableSample> sine;
        wearable_sine(def, WearableSineDef{}, 0.5, &sine);  // the seed's Fig. 8: 0.15 sin(pi t) + 0.15 N
        write_file(o.output, samples_csv(sine));
        const WearableBandwidthResult bw = wearable_bandwidth(def);
        json += "  \"bandwidth_hz\": " + (bw.found ? fmt("%.6g", bw.bandwidth_hz) : std::string("null")) +
                ",\n  \"seed\": {\"bandwidth_hz\": 3.5},\n  \"sweep\": [";
        for (std::size_t k = 0; k < bw.sweep.size(); ++k) {
            const WearableSineResponse& s = bw.sweep[k];
            json += std::string(k ? ",\n    " : "\n    ") + "{\"freq_hz\": " + fmt("%.6g", s.freq) + ", \"gain\": " + fmt("%.6g", s.gain) +
                    ", \"phase_deg\": " + fmt("%.6g", s.phase * 57.29577951308232) + "}";
        }
        json += "\n  ]\n}\n";
        if (bw.found)
            std::fprintf(stderr, "simulate: wearable Q_r sine sweep bandwidth (-3 dB) %.2f Hz (seed 003: about 3.5 Hz)\n", bw.bandwidth_hz);
        else
            std::fprintf(stderr, "simulate: wearable gain stayed above -3 dB up to %.1f Hz\n", bw.sweep.back().freq);
        std::fprintf(stderr, "simulate: the seed's 0.15 sin(pi t) + 0.15 N run written to %s\n", o.output.c_str());
    } else {
        CurvatureArcDef cd;
        arc_of(scene, cd.chord, cd.height);
        if (!(o.task_speed > 0.0 && o.task_speed <= 1.0)) throw BadInput("--task-speed: must be in (0, 1] m/s");
        cd.speed = o.task_speed;
        CurvatureArcResult r;
        try {
            r = curvature_arc(def, cd);
        } catch (const std::invalid_argument& e) {
            throw BadInput(e.what());
        }
        std::string csv = "t,contact_x,surface_angle,platform_tilt,platform_force,Q_1,Q_2,Q_3,contact,fault\n";
        char line[256];
        for (const CurvatureSample& s : r.samples) {
            std::snprintf(line, sizeof line, "%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%d,%d\n", s.t, s.contact_x, s.surface_angle,
                          s.platform_tilt, s.platform_force, s.tension(0), s.tension(1), s.tension(2), s.contact ? 1 : 0,
                          s.fault ? 1 : 0);
            csv += line;
        }
        write_file(o.output, csv);
        json += "  \"chord_m\": " + fmt("%.6g", cd.chord) + ",\n  \"height_m\": " + fmt("%.6g", cd.height) + ",\n  \"radius_m\": " +
                fmt("%.6g", r.radius) + ",\n  \"speed_m_s\": " + fmt("%.6g", cd.speed) + ",\n  \"max_surface_angle_rad\": " +
                fmt("%.6g", r.max_surface_angle) + ",\n  \"tilt_rms_rad\": " + fmt("%.6g", r.tilt_rms) +
                ",\n  \"tilt_max_error_rad\": " + fmt("%.6g", r.tilt_max_error) + ",\n  \"fault\": " + (r.fault ? "true" : "false") + "\n}\n";
        std::fprintf(stderr, "simulate: curvature arc d %.3f m, h %.1f mm (r_a %.3f m, slope up to %.3f rad): platform tilt "
                     "rms error %.4f rad, max %.4f rad%s\n", cd.chord, cd.height * 1e3, r.radius, r.max_surface_angle,
                     r.tilt_rms, r.tilt_max_error, r.fault ? "; a fault occurred" : "");
    }
    if (!o.json.empty()) write_file(o.json, json);
    std::fprintf(stderr, "simulate: written to %s%s%s\n", o.output.c_str(), o.json.empty() ? "" : " and ", o.json.c_str());
    return 0;
}

}  // namespace contactlab::app
