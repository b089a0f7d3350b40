// scene_overrides.hpp — the scene's values a command line replaces (--stiffness, --radius,
// --force-model, --friction, ...), shared by `trace`, `demo` and `simulate`: the options as CLI11
// reads them, and their application to a loaded scene, re-validated, with a bad value named by
// its option.
#pragma once

#include "haptics/scene.hpp"

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace contactlab::app {

// Values given on the command line replace the scene file's (SI units).
struct SceneOverrides {
    std::optional<double> stiffness;  // N/m   (--stiffness)
    std::optional<double> radius;     // m     (--radius)
    std::optional<double> length;     // m     (--length)
    std::optional<double> max_force;  // N     (--max-force)
    std::optional<std::string> curve_mode;  // exact | flatten (--curve-mode)
    std::optional<double> tolerance;        // m, flatten chord tolerance (--tolerance)
    std::optional<std::string> force_model; // spring | ellipsoid (--force-model)
    std::optional<double> k_tangential;     // N/m (--k-tangential)
    std::optional<double> k_normal;         // N/m (--k-normal)
    std::optional<double> eccentricity;     // k_normal / k_tangential (--eccentricity)
    std::optional<double> total_stiffness;  // N/m, seed 004 eq. 3 (--total-stiffness)
    std::optional<double> friction;         // static coefficient (--friction)
    std::optional<double> friction_dynamic; // dynamic coefficient, default = static (--friction-dynamic)
    std::optional<double> damping;          // N s/m (--damping)
    std::optional<std::string> contact_force; // proxy | sum: force with two contacts (--contact-force)
};

// Adds the override options to a subcommand; CLI11 keeps pointers into `o` until parsing ends.
void add_override_options(CLI::App* cmd, SceneOverrides& o);

// Applies the overrides and re-validates; a bad value throws SceneError naming the option.
void apply_overrides(Scene& scene, const SceneOverrides& o);

}  // namespace contactlab::app
