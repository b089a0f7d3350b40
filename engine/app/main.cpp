// main.cpp — the `contactlab` executable: command line (CLI11) and exit codes.
//
// Each subcommand lives in its own file and registers itself here (subcommands.hpp). With no
// arguments at all, `contactlab` opens the editor (`contactlab edit`).
// Exit codes: 0 success; 2 bad input (scene file, CSV, option value, usage); 1 anything else.
#include "engine/app/subcommands.hpp"
#include "engine/app/trace_csv.hpp"
#include "haptics/scene_io.hpp"

#include <contactlab/version.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    using namespace contactlab;
    using namespace contactlab::app;
    CLI::App app{"ContactLab — haptic display of contact location: scenes, proxy, traces."};
    // "contactlab 0.1.0" and, from a git checkout, the commit: results must name what made them.
    std::string version = std::string("contactlab ") + CONTACTLAB_VERSION;
    if (*CONTACTLAB_GIT_COMMIT) version += std::string(" (commit ") + CONTACTLAB_GIT_COMMIT + ")";
    app.set_version_flag("--version", version);
    app.require_subcommand(0, 1);

    int rc = 0;
    // One line per subcommand file.
    register_trace_commands(app, rc);
    register_generate_command(app, rc);
    register_simulate_command(app, rc);
    register_render_command(app, rc);
    register_bench_command(app, rc);
    register_edit_command(app, rc);
    register_devices_command(app, rc);
    register_fuzz_contact_command(app, rc);
    register_experiment_command(app, rc);
    register_experiment_power_command(app, rc);
    register_experiment_merge_command(app, rc);
    register_experiment_calibrate_command(app, rc);
    register_experiment_slurm_command(app, rc);
    register_falcon_kinematics_command(app, rc);
    register_haply_kinematics_command(app, rc);

    try {
        app.parse(argc, argv);
        if (argc == 1) return run_edit_command();
        if (app.get_subcommands().empty()) throw CLI::RequiredError("a subcommand");
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kExitBadInput;
    } catch (const BadInput& e) {
        std::fprintf(stderr, "contactlab: error: %s\n", e.what());
        return kExitBadInput;
    } catch (const SceneError& e) {
        std::fprintf(stderr, "contactlab: error: %s\n", e.what());
        return kExitBadInput;
    } catch (const CsvError& e) {
        std::fprintf(stderr, "contactlab: error: %s\n", e.what());
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "contactlab: error: %s\n", e.what());
        return 1;
    }
    return rc;
}
