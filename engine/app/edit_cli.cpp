// edit_cli.cpp — the `edit` subcommand (also what `contactlab` with no arguments runs): the
// interactive editor (engine/editor). Needs a display; without one it says how to run it under
// xvfb-run and which subcommands work headless, and exits 2.
#include "engine/app/number_options.hpp"
#include "engine/app/subcommands.hpp"
#include "haptics/parameter_limits.hpp"
#include "engine/editor/editor.hpp"
#include "engine/editor/script.hpp"
#include "engine/experiments/base/path_name.hpp"
#include "engine/experiments/base/results_table.hpp"
#include "engine/render/vk_check.hpp"

namespace contactlab::app {
namespace {

editor::EditorOptions& edit_options() {
    static editor::EditorOptions o;  // outlives parsing; one process, one parse
    return o;
}

}  // namespace

int run_edit_command() {
    const editor::EditorOptions& o = edit_options();
    if (o.width < 64 || o.width > 16384 || o.height < 64 || o.height > 16384)
        throw BadInput("--width/--height: must be in 64..16384 px");
    if (!o.screenshot.empty() && o.frames <= 0 && o.script.empty())
        throw BadInput("--screenshot needs --frames N (the screenshot is the last frame)");
    if (o.frames < 0) throw BadInput("--frames: must be at least 1");
    if (!(o.rate >= limits::kMinServoRate && o.rate <= limits::kMaxRealtimeServoRate))
        throw BadInput("--rate: must be between 100 and 20000 Hz");  // haptics/parameter_limits.hpp
    if (o.experiment.empty() != o.participant.empty())
        throw BadInput("--experiment and --participant go together (a protocol and the person's id, e.g. P07)");
    // The id names the default results file (PROTOCOL-ID.csv): refused here, before a window opens.
    if (const std::string why = experiments::path_name_problem(o.participant); !o.participant.empty() && !why.empty())
        throw BadInput("--participant: the id " + why + " (it is part of a file name), e.g. P07, got \"" +
                       experiments::escaped_name(o.participant) + "\"");
    try {
        return editor::run_editor(o);
    } catch (const experiments::ExperimentError& e) {
        throw BadInput(e.what());
    } catch (const editor::ScriptError& e) {
        throw BadInput(e.what());
    } catch (const render::NoVulkanDevice& e) {
        throw BadInput(e.what());
    }
}

void register_edit_command(CLI::App& app, int& rc) {
    editor::EditorOptions& o = edit_options();
    CLI::App* cmd = app.add_subcommand("edit", "Interactive editor: draw scenes, move the finger, tune the servo live "
                                               "(needs a display; headless: xvfb-run -a contactlab edit)");
    cmd->add_option("scene", o.scene_path, "Scene file (JSON, scenes/README.md); a new file if it does not exist");
    cmd->add_option("--width", o.width, "Window width (px)")->default_val(1280);
    cmd->add_option("--height", o.height, "Window height (px)")->default_val(720);
    cmd->add_option("--frames", o.frames, "Render N frames, then exit 0 (smoke tests, timing)");
    cmd->add_option("--screenshot", o.screenshot, "With --frames: write the last frame, read back from the swapchain, as PNG");
    cmd->add_option("--script", o.script, "Run UI actions and checks from FILE (engine/editor/script.hpp), then exit");
    cmd->add_option("--timeout", o.timeout, "Give up (exit 1) after this many seconds");
    cmd->add_option("--rate", o.rate, "Servo rate (Hz), 100..20000")->default_val(1000.0);
    cmd->add_option("--device", o.device,
                    "Device the servo starts on: mouse (default), sim-cld, sim-wearable, replay:FILE, usb:hapio, usb:falcon, usb:haply "
                    "(one that does not open leaves the mouse running and says why)")
        ->default_val("mouse");
    cmd->add_option("--autosave", o.autosave_interval, "Seconds between writes of the recovery file")->default_val(30.0);
    cmd->add_option("--experiment", o.experiment, "Run this protocol's trials live (scenes/experiments/); needs --participant");
    cmd->add_option("--participant", o.participant, "The person's id in the results (e.g. P07)");
    add_whole_option(cmd, "--seed", o.experiment_seed, 0, kMaxSeed, "Seed of the experiment's trial order");
    cmd->add_option("--results", o.results, "Results CSV, written row by row (default PROTOCOL-ID.csv); resumed if it exists");
    cmd->add_flag("--software", o.software, "Use the CPU Vulkan device (lavapipe)");
    cmd->add_flag("--validation,!--no-validation", o.validation,
                  "Vulkan validation layers; any validation message makes the exit code 1");
    cmd->add_flag("!--no-vsync", o.vsync, "Present without vsync (MAILBOX/IMMEDIATE) to measure frame rates");
    cmd->callback([&rc] { rc = run_edit_command(); });
}

}  // namespace contactlab::app
