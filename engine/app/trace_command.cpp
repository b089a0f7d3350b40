// trace_command.cpp — the proxy run behind `contactlab trace` and `contactlab demo`.
#include "engine/app/trace_command.hpp"

#include "haptics/environment.hpp"
#include "haptics/scene_io.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <unistd.h>

namespace contactlab::app {

void apply_overrides(Scene& scene, const SceneOverrides& o) {
    std::string given;
    auto note = [&](const char* name, std::optional<double> v) {
        if (v) given += std::string(given.empty() ? "" : ", ") + name + " " + exact(*v);
    };
    note("--stiffness", o.stiffness);
    note("--radius", o.radius);
    note("--length", o.length);
    note("--max-force", o.max_force);
    note("--tolerance", o.tolerance);
    if (o.curve_mode) {
        given += std::string(given.empty() ? "" : ", ") + "--curve-mode " + *o.curve_mode;
        const std::optional<CurveMode> named = curve_mode_named(*o.curve_mode);
        if (!named) throw SceneError("command-line options (" + given + "): expected exact or flatten");
        scene.curves.mode = *named;
    }
    if (o.tolerance) scene.curves.tolerance = *o.tolerance;
    note("--k-tangential", o.k_tangential);
    note("--k-normal", o.k_normal);
    note("--eccentricity", o.eccentricity);
    note("--total-stiffness", o.total_stiffness);
    note("--friction", o.friction);
    note("--friction-dynamic", o.friction_dynamic);
    note("--damping", o.damping);
    ForceLaw& law = scene.force.law;
    if (o.force_model) {
        given += std::string(given.empty() ? "" : ", ") + "--force-model " + *o.force_model;
        // As in the editor: the switch keeps the stiffness felt pressing straight in (scene.hpp).
        if (*o.force_model == "spring") {
            set_force_model(scene.force, ForceModel::spring);
        } else if (*o.force_model == "ellipsoid") {
            set_force_model(scene.force, ForceModel::ellipsoid);
        } else {
            throw SceneError("command-line options (" + given + "): expected spring or ellipsoid");
        }
    }
    if (o.contact_force) {
        given += std::string(given.empty() ? "" : ", ") + "--contact-force " + *o.contact_force;
        if (*o.contact_force == "proxy") {
            law.contacts = ContactForce::proxy;
        } else if (*o.contact_force == "sum") {
            law.contacts = ContactForce::sum;
        } else {
            throw SceneError("command-line options (" + given + "): expected proxy or sum");
        }
    }
    if (o.eccentricity || o.total_stiffness) {
        if (!o.eccentricity || !o.total_stiffness)
            throw SceneError("command-line options (" + given + "): --eccentricity and --total-stiffness go together");
        if (!(*o.eccentricity > 0.0) || *o.eccentricity > 1e3)
            throw SceneError("command-line options (" + given + "): --eccentricity must lie in (0, 1000]");
        law.k_tangential = tangential_stiffness_from(*o.total_stiffness, *o.eccentricity);
        law.k_normal = *o.eccentricity * law.k_tangential;
    }
    if (o.k_tangential) law.k_tangential = *o.k_tangential;
    if (o.k_normal) law.k_normal = *o.k_normal;
    if (o.friction) {
        law.mu_static = *o.friction;
        law.mu_dynamic = o.friction_dynamic ? *o.friction_dynamic : *o.friction;
    } else if (o.friction_dynamic) {
        law.mu_dynamic = *o.friction_dynamic;
    }
    if (o.damping) law.damping = *o.damping;
    if (o.stiffness) scene.force.stiffness = *o.stiffness;
    if (o.radius) scene.finger.radius = *o.radius;
    if (o.length) scene.finger.length = *o.length;
    if (o.max_force) scene.force.max_force = *o.max_force;
    try {
        validate_scene(scene);
    } catch (const SceneError& e) {
        if (given.empty()) throw;
        throw SceneError("command-line options (" + given + "): " + e.what());
    }
}

std::vector<ProxyOutput> run_trace(const Scene& scene, const std::vector<FingerSample>& samples) {
    const Environment env = build_environment(scene);
    const ProxyDef def = proxy_def_of(scene);
    Proxy proxy(env, def);
    std::vector<ProxyOutput> out;
    out.reserve(samples.size());
    double previous_t = samples.empty() ? 0.0 : samples.front().t - kDefaultServoPeriod;
    for (const FingerSample& s : samples) {
        out.push_back(proxy.update(s.x, s.phi, s.t - previous_t));  // dt from the file's times
        previous_t = s.t;
    }
    return out;
}

void write_trace_file(const std::string& path, const std::vector<FingerSample>& samples,
                      const std::vector<ProxyOutput>& outputs) {
    std::string tmp = path + ".tmp-XXXXXX";
    const int fd = ::mkstemp(tmp.data());
    if (fd < 0) throw std::runtime_error(path + ": cannot create (" + std::strerror(errno) + ")");
    std::FILE* f = ::fdopen(fd, "w");
    if (!f) {
        ::close(fd);
        ::unlink(tmp.c_str());
        throw std::runtime_error(path + ": cannot open for writing");
    }
    write_trace_header(f);
    for (std::size_t i = 0; i < outputs.size(); ++i) write_trace_row(f, samples[i].t, outputs[i]);
    const bool ok = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0 && !std::ferror(f);
    const bool closed = std::fclose(f) == 0;
    if (!ok || !closed || ::rename(tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(tmp.c_str());
        throw std::runtime_error(path + ": write failed (" + std::strerror(err) + ")");
    }
}

DemoRun run_contour_follow(const Scene& scene, double x0, double speed, double press, double duration) {
    const Environment env = build_environment(scene);
    const ProxyDef def = proxy_def_of(scene);
    Proxy proxy(env, def);
    const double dt = 1e-3;          // s: the 1 kHz servo rate of seed 000
    const double max_phi_rate = 1.0; // rad/s
    DemoRun run;
    Vec2 x{x0, env.bounds.hi.y + def.finger.radius + 0.02};
    double phi = 0.0;
    const int ticks = static_cast<int>(duration / dt);
    for (int k = 0; k < ticks; ++k) {
        const ProxyOutput& o = proxy.update(x, phi);
        run.samples.push_back({k * dt, x, phi});
        run.outputs.push_back(o);
        if (!o.contact) {  // free space: move straight down toward the surface
            x.y -= speed * dt;
            continue;
        }
        const Vec2 n = glm::normalize(o.force);   // free-side contact normal
        const Vec2 tangent{n.y, -n.x};            // solid on the right: travel with it there
        x = o.proxy - press * n + speed * dt * tangent;
        const double phi_goal = angle_of(n) - 0.5 * kPi;  // pad middle faces the surface
        phi += std::clamp(wrap_pi(phi_goal - phi), -max_phi_rate * dt, max_phi_rate * dt);
    }
    return run;
}

}  // namespace contactlab::app
