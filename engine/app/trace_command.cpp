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
