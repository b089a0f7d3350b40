// subcommands.hpp — how subcommand files plug into `contactlab` (engine/app/main.cpp).
//
// Each subcommand file defines one register_* function that adds its CLI11 subcommand(s) to the
// app; the callback stores its exit code in `rc`. Errors: throw BadInput (or SceneError /
// CsvError) for anything the user can fix (exit 2); other exceptions exit 1. Input files that ship
// with ContactLab (scenes, protocols) go through installed_data_path (data_path.hpp).
#pragma once

#include "engine/app/data_path.hpp"
#include "engine/app/scene_overrides.hpp"
#include "engine/app/trace_command.hpp"

#include <CLI/CLI.hpp>

#include <stdexcept>

namespace contactlab::app {

inline constexpr int kExitBadInput = 2;

// A bad option value or input file not covered by SceneError/CsvError: exit code 2.
struct BadInput : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void register_trace_commands(CLI::App& app, int& rc);  // trace, demo (trace_cli.cpp)
void register_generate_command(CLI::App& app, int& rc);  // generate (generate_cli.cpp)
void register_simulate_command(CLI::App& app, int& rc);  // simulate (simulate_cli.cpp)
void register_render_command(CLI::App& app, int& rc);  // render (render_cli.cpp)
void register_bench_command(CLI::App& app, int& rc);   // bench (bench_cli.cpp)
void register_edit_command(CLI::App& app, int& rc);  // edit (edit_cli.cpp)
// `edit` with its defaults: what `contactlab` with no arguments runs (edit_cli.cpp).
int run_edit_command();
void register_devices_command(CLI::App& app, int& rc);  // devices (devices_cli.cpp)
void register_fuzz_contact_command(CLI::App& app, int& rc);  // fuzz-contact (fuzz_contact_cli.cpp)
void register_experiment_command(CLI::App& app, int& rc);  // experiment run|analyze (experiment_cli.cpp)
// experiment power (experiment_power_cli.cpp); after register_experiment_command, whose subcommand it joins
void register_experiment_power_command(CLI::App& app, int& rc);
// experiment merge (experiment_merge_cli.cpp); after register_experiment_command, as power
void register_experiment_merge_command(CLI::App& app, int& rc);
// experiment calibrate (experiment_calibrate_cli.cpp); after register_experiment_command
void register_experiment_calibrate_command(CLI::App& app, int& rc);
// experiment slurm (experiment_slurm_cli.cpp); after register_experiment_command
void register_experiment_slurm_command(CLI::App& app, int& rc);
void register_falcon_kinematics_command(CLI::App& app, int& rc);  // falcon-kinematics (falcon_kinematics_cli.cpp)
void register_haply_kinematics_command(CLI::App& app, int& rc);   // haply-kinematics (haply_kinematics_cli.cpp)

}  // namespace contactlab::app
