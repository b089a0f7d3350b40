// simulate_cli.cpp — the `simulate` subcommand on the command line.
#include "engine/app/simulate_command.hpp"
#include "engine/app/subcommands.hpp"

namespace contactlab::app {

void register_simulate_command(CLI::App& app, int& rc) {
    static SimulateOptions o;  // outlives parsing; one process, one parse
    static bool virtual_time = false, real_time = false;
    CLI::App* cmd = app.add_subcommand("simulate", "Run the servo loop against a simulated or replayed device");
    cmd->add_option("scene", o.scene_path, "Scene file (JSON, scenes/README.md)")->required();
    cmd->add_option("--device", o.device, "sim-cld (simulated CLD rig + scripted hand), sim-wearable (seed 003's platform under a finger that follows --hand, or its --task), replay:FILE, "
                    "usb:hapio, usb:falcon or usb:haply (real devices: real time, need --duration)")
        ->default_val("sim-cld");
    cmd->add_option("--firmware", o.firmware,
                    "usb:falcon: Novint's Falcon firmware file, uploaded when the Falcon has none running (not shipped)");
    cmd->add_option("--haply-hardware", o.haply_hardware,
                    "usb:haply: the Haply 2DIY's board generation, 3 (current) or 2")
        ->default_val(3);
    cmd->add_option("--haply-port", o.haply_port,
                    "usb:haply: the board's serial port (e.g. /dev/ttyACM0); default: found by its USB id");
    cmd->add_option("--device-file", o.device_file,
                    "usb:*: a JSON file declaring what the device does not report: {\"effective_mass_kg\": M} (kg, "
                    "measured), which \"passivity\": \"control\" needs on the Falcon, the 2DIY and version 1 hapio boards");
    cmd->add_option("--hand", o.hand, "Scripted hand path, header t,x,y,phi (s, m, m, rad), linearly interpolated");
    cmd->add_option("--task", o.task, "Built-in task instead of --hand: contour-block (seed 000 Fig. 9), or roller-bandwidth "
                                        "(the roller alone, 1 cm sine sweep; writes freq,gain,phase_deg,element_gain,max_error); "
                                        "seed 003 on sim-wearable: wearable-step (0.3 N step), wearable-bandwidth (Q_r sine "
                                        "sweep; writes the 0.5 Hz run), curvature-arc (the scene's arc moves under the "
                                        "finger at --task-speed; writes t,contact_x,surface_angle,platform_tilt,"
                                        "platform_force,Q_1,Q_2,Q_3,contact,fault)");
    cmd->add_option("--task-speed", o.task_speed, "Hand speed on the built-in task (m/s)")->default_val(0.05);
    cmd->add_option("--rate", o.rate, "Servo rate (Hz), 100..20000")->default_val(1000.0);
    cmd->add_option("--roller-travel", o.roller_travel,
                    "Roller travel the servo may use (m), centred on the pad: 0.018 is seed 002's software "
                    "limit; default the device's full travel (sim-cld 0.020)")
        ->each([](const std::string&) { o.roller_travel_set = true; });
    cmd->add_option("--duration", o.duration, "Simulated time (s); default: the path's or recording's length");
    auto* v = cmd->add_flag("--virtual", virtual_time, "Virtual time: no sleeping, bit-identical runs (default)");
    auto* r = cmd->add_flag("--realtime", real_time, "Real time: a servo thread at the rate, with period statistics");
    v->excludes(r);
    cmd->add_option("--output,-o", o.output,
                    "Per-tick CSV: t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d,roller_l,roller_target,period,roller_drive,state,"
                    "e_hold,e_field,e_turn,e_edit,e_proxy,e_friction,e_damping,e_generated,observer_energy,observer_margin (J)")
        ->required();
    cmd->add_option("--record", o.record, "Also record every tick (contactlab recording v1) for --device replay:FILE");
    cmd->add_option("--json", o.json, "Wearable tasks: write the summary (rise_time_s, steady_error_pct, bandwidth_hz, "
                                      "tilt_rms_rad, ...) as JSON");
    cmd->add_option("--wearable-fit", o.wearable_fit, "Wearable tasks: seed (references shaped to the seed's measured "
                                                      "45 ms response) or none (Table 1's motor alone)")
        ->default_val("seed");
    cmd->add_option("--fsr-noise", o.fsr_noise, "Wearable tasks: FSR noise standard deviation (N)")->default_val(0.003);
    add_override_options(cmd, o.overrides);
    cmd->callback([&rc] {
        o.realtime = real_time;
        o.scene_path = installed_data_path(o.scene_path);
        rc = run_simulate(o);
    });
}

}  // namespace contactlab::app
