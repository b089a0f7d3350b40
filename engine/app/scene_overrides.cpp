// scene_overrides.cpp — command-line values replacing the scene's (scene_overrides.hpp).
#include "engine/app/scene_overrides.hpp"

#include "haptics/finger_samples_csv.hpp"
#include "haptics/scene_io.hpp"

#include <CLI/CLI.hpp>

namespace contactlab::app {

void add_override_options(CLI::App* cmd, SceneOverrides& o) {
    cmd->add_option("--stiffness", o.stiffness, "Contact stiffness Ke (N/m); replaces the scene's force.stiffness");
    cmd->add_option("--radius", o.radius, "Finger pad radius R (m); replaces finger.radius");
    cmd->add_option("--length", o.length, "Finger pad arc length L (m); replaces finger.length");
    cmd->add_option("--max-force", o.max_force, "Force magnitude clamp (N); replaces force.max_force");
    cmd->add_option("--curve-mode", o.curve_mode,
                    "Curves: exact (arc spline within 1e-7 m, contacts refined on the true curve) or flatten (chords)");
    cmd->add_option("--tolerance", o.tolerance, "Chord tolerance (m) of --curve-mode flatten; replaces curves.tolerance");
    cmd->add_option("--force-model", o.force_model, "spring (F = Ke d) or ellipsoid (seed 004's pseudo-ellipsoidal field)");
    cmd->add_option("--k-tangential", o.k_tangential, "Ellipsoid: tangential stiffness k1 (N/m)");
    cmd->add_option("--k-normal", o.k_normal, "Ellipsoid: normal stiffness k2 (N/m)");
    cmd->add_option("--eccentricity", o.eccentricity, "Ellipsoid: e = k2 / k1 (with --total-stiffness)");
    cmd->add_option("--total-stiffness", o.total_stiffness, "Ellipsoid: k = sqrt((k1^2 + 2 k2^2) / 3) (N/m), seed 004 eq. 3");
    cmd->add_option("--friction", o.friction, "Friction cone: static coefficient (the dynamic one defaults to it)");
    cmd->add_option("--friction-dynamic", o.friction_dynamic, "Friction cone: dynamic coefficient (<= static)");
    cmd->add_option("--damping", o.damping, "Normal damping B (N s/m)");
    cmd->add_option("--contact-force", o.contact_force,
                    "Two contacts: proxy (one spring to the proxy) or sum (each contact's own spring, seed 002)");
}

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

}  // namespace contactlab::app
