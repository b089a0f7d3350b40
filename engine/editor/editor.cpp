// editor.cpp — the editor's frame loop: events -> ImGui + canvas (or script) -> servo publish ->
// draw list (the shared scene drawer + the editor's marks) -> window target (+ ImGui) -> present.
#include "engine/editor/editor.hpp"
#include "drivers/servo_loop.hpp"
#include "engine/editor/cursor_wearable_device.hpp"
#include "engine/editor/x_server_affinity.hpp"

#include "engine/editor/canvas.hpp"
#include "engine/editor/display.hpp"
#include "engine/editor/editor_state.hpp"
#include "engine/editor/haptics_commands.hpp"
#include "engine/editor/imgui_layer.hpp"
#include "engine/editor/panels.hpp"
#include "engine/editor/device_sections.hpp"
#include "engine/editor/panel_parts.hpp"
#include "engine/editor/redraw_policy.hpp"
#include "engine/editor/experiment_mode.hpp"
#include "engine/experiments/runs/run_meta.hpp"
#include "engine/editor/recovery.hpp"
#include "engine/editor/rulers.hpp"
#include "engine/editor/scene_layer_key.hpp"
#include "engine/editor/script.hpp"
#include "engine/editor/servo_view.hpp"
#include "engine/editor/window.hpp"
#include "engine/editor/window_target.hpp"
#include "engine/render/finger_state.hpp"
#include "engine/render/vk_check.hpp"
#include "haptics/scene_io.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <chrono>
#include <cstdlib>
#include <sched.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace contactlab::editor {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

const char* present_mode_name(VkPresentModeKHR m) {
    switch (m) {
        case VK_PRESENT_MODE_FIFO_KHR: return "FIFO (vsync)";
        case VK_PRESENT_MODE_MAILBOX_KHR: return "MAILBOX";
        case VK_PRESENT_MODE_IMMEDIATE_KHR: return "IMMEDIATE";
        default: return "other";
    }
}

// The document to start with: the file, a new scene at that path, or (file unreadable) an empty
// scene with the problem reported in the window.
// With `strict` (--frames, --script: nobody is there to read the window) a scene that does not
// load is an error instead (SceneError: exit 2).
void open_initial(EditorState& s, const std::string& path, bool strict) {
    if (path.empty()) {
        s.say("new scene: draw with the Line tool (3), move the finger with the Finger tool (1)");
    } else if (!std::filesystem::exists(path)) {
        s.doc = Document(Scene{}, path);
        s.say("new scene; Save writes " + path);
    } else {
        try {
            s.doc.open(path);
            s.say("opened " + path);
        } catch (const SceneError& e) {
            if (strict) throw;
            s.say(std::string("could not open: ") + e.what(), true);
            std::fprintf(stderr, "contactlab edit: %s\n", e.what());
        }
    }
    // Named, new or untitled: work an earlier session left unsaved is offered, never overwritten.
    offer_recovery(s);
    for (const std::string& f : s.recovery_offers)
        std::fprintf(stderr, "contactlab edit: unsaved work from an earlier session: %s\n", recovery_summary(f).c_str());
}

// A finger start above the scene: free space, so the servo arms and ramps in before contact.
MousePose initial_pose(const Scene& scene) {
    MousePose p;
    const Environment env = build_environment(scene);
    if (!scene.contours.empty()) {
        const render::FingerPose fp = render::default_finger_pose(env, proxy_def_of(scene));
        p.finger = fp.center + Vec2(0.0, 0.5 * scene.finger.radius);
    } else {
        p.finger = Vec2(0.0, 0.03);
    }
    return p;
}

// Pixels whose colour differs between two pictures of one size (all of them if the sizes differ).
long count_differing_pixels(const render::Image& a, const render::Image& b) {
    if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
        return static_cast<long>(std::max(a.rgba.size(), b.rgba.size()) / 4);
    long n = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4)
        if (a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2]) ++n;
    return n;
}

void handle_real_input(EditorState& s, GLFWwindow* window) {
    ImGuiIO& io = ImGui::GetIO();
    const double sx = io.DisplayFramebufferScale.x, sy = io.DisplayFramebufferScale.y;
    if (!io.WantCaptureKeyboard) {
        const bool ctrl = io.KeyCtrl;
        struct K { int key; const char* name; const char* ctrl_name; };
        static const K keys[] = {
            {GLFW_KEY_SPACE, "space", nullptr}, {GLFW_KEY_DELETE, "delete", nullptr},
            {GLFW_KEY_BACKSPACE, "delete", nullptr}, {GLFW_KEY_Z, "z", "ctrl+z"},
            {GLFW_KEY_Y, nullptr, "ctrl+y"}, {GLFW_KEY_S, nullptr, "ctrl+s"},
            {GLFW_KEY_ESCAPE, "escape", nullptr}, {GLFW_KEY_F, "f", nullptr},
            {GLFW_KEY_1, "1", nullptr}, {GLFW_KEY_2, "2", nullptr}, {GLFW_KEY_3, "3", nullptr},
            {GLFW_KEY_4, "4", nullptr}, {GLFW_KEY_5, "5", nullptr}, {GLFW_KEY_6, "6", nullptr},
            {GLFW_KEY_7, "7", nullptr},
            {GLFW_KEY_Q, "q", "ctrl+q"}, {GLFW_KEY_E, "e", nullptr},
            {GLFW_KEY_P, "p", nullptr}, {GLFW_KEY_ENTER, "enter", nullptr}, {GLFW_KEY_8, "8", nullptr},
            {GLFW_KEY_9, "9", nullptr},
        };
        for (const K& k : keys) {
            if (!ImGui::IsKeyPressed(k.key)) continue;
            const char* name = ctrl ? k.ctrl_name : k.name;
            if (!name) continue;
            if (std::string(name) == "ctrl+q") s.quit = true;
            else if (!experiment_key(s, name, s.now)) canvas_key(s, name);
        }
    }
    (void)window;
    const double x = io.MousePos.x * sx, y = io.MousePos.y * sy;
    const bool valid_pos = io.MousePos.x > -1e6f && io.MousePos.y > -1e6f;
    static const Button buttons[3] = {Button::left, Button::right, Button::middle};
    // Releases always reach the canvas (a drag may end over a panel); the rest only off-panel.
    for (int b = 0; b < 3; ++b)
        if (ImGui::IsMouseReleased(b)) canvas_release(s, buttons[b], x, y);
    if (io.WantCaptureMouse || !valid_pos) return;
    if (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f) canvas_move(s, x, y);
    for (int b = 0; b < 3; ++b)
        if (ImGui::IsMouseClicked(b)) canvas_press(s, buttons[b], x, y);
    if (io.MouseWheel != 0.0f) canvas_wheel(s, x, y, io.MouseWheel, io.KeyShift || io.KeyCtrl);
}

struct FrameTimer {
    Clock::time_point window_start = Clock::now();
    int window_frames = 0;
    double window_busy = 0.0;  // s of CPU-side frame work in the window
    double frame_ms = 0.0, fps = 0.0;
    // Whole run.
    long frames = 0;
    double busy = 0.0;
    Clock::time_point first = Clock::now();

    void add(double busy_s) {
        ++window_frames;
        window_busy += busy_s;
        ++frames;
        busy += busy_s;
        const double w = since(window_start);
        if (w >= 1.0) {
            frame_ms = 1e3 * window_busy / window_frames;
            fps = window_frames / w;
            window_start = Clock::now();
            window_frames = 0;
            window_busy = 0.0;
        }
    }
};

}  // namespace

int run_editor(const EditorOptions& o) {
    const Clock::time_point t_start = Clock::now();
    Script script;
    const bool scripted = !o.script.empty();
    if (scripted) script = Script::load(o.script);  // ScriptError: bad input, before any window

    // GLFW: no display -> the clear message, exit 2.
    GlfwSession glfw;
    if (!glfw.ok()) {
        std::fputs(no_display_message(glfw.reason()).c_str(), stderr);
        return kExitNoDisplay;
    }

    EditorState s;
    open_initial(s, o.scene_path, scripted || o.frames > 0);
    // Live trials (--experiment): the session reads the protocol and any results written before.
    ExperimentState experiment;
    if (!o.experiment.empty()) {
        const experiments::Protocol protocol = experiments::load_protocol(o.experiment);
        const std::string results = !o.results.empty() ? o.results
                                    : std::filesystem::path(o.experiment).stem().string() + "-" + o.participant + ".csv";
        experiment.session = std::make_unique<experiments::LiveSession>(protocol, o.participant, o.experiment_seed, results);
        s.experiment = &experiment;
        // Provenance beside the results (run_meta.hpp): program, protocol file and its SHA-256,
        // seed, participant, the device and rate the session started with (each row names the
        // device its trial was felt on); a session started again adds when.
        experiments::RunIdentity id;
        id.protocol_path = o.experiment;
        id.protocol = &experiment.session->protocol();
        id.seed = o.experiment_seed;
        id.participants = {o.participant};
        id.device = o.device;
        id.servo_rate_hz = o.rate;
        id.traces = false;
        const std::string command = "contactlab edit --experiment " + o.experiment + " --participant " + o.participant +
                                    " --seed " + std::to_string(o.experiment_seed) + " --results " + results +
                                    " --device " + o.device;
        auto meta = experiments::read_meta(results);
        if (meta) experiments::note_resume(*meta, command);
        else meta = experiments::make_meta(id, command);
        experiments::write_meta(results, *meta);
        char buf[256];
        std::snprintf(buf, sizeof buf, "experiment: %s, participant %s, %zu of %zu trials done, results in %s",
                      protocol.name.c_str(), o.participant.c_str(), experiment.session->done(), experiment.session->total(),
                      results.c_str());
        std::fprintf(stderr, "contactlab edit: %s\n", buf);
        s.say(buf);
    }

    // Threads: one core for the servo, the rest (the Vulkan driver's threads included) for the
    // renderer and the UI. Lavapipe starts one rasteriser thread per core unless told otherwise.
    const int servo_core = reserve_servo_core();
    if (servo_core >= 0 && !std::getenv("LP_NUM_THREADS")) {
        cpu_set_t set;
        CPU_ZERO(&set);
        sched_getaffinity(0, sizeof set, &set);
        setenv("LP_NUM_THREADS", std::to_string(CPU_COUNT(&set)).c_str(), 0);
    }

    Window window(o.width, o.height, "ContactLab editor");
    // The X server too, when it is a local Xvfb (x_server_affinity.hpp: its frame copies ran on
    // the servo's core and made the late ticks).
    const std::string x_affinity = keep_x_server_off_core(servo_core);
    if (!x_affinity.empty()) std::fprintf(stderr, "contactlab edit: %s\n", x_affinity.c_str());
    render::ContextOptions copt;
    copt.software = o.software;
    copt.validation = o.validation;
    render::WindowSupport wsup;
    wsup.instance_extensions = window_instance_extensions();
    wsup.swapchain = true;
    render::VulkanContext ctx(copt, wsup);
    Surface surface(ctx.instance(), window);
    WindowTarget target(ctx, surface.handle(), o.vsync);
    // --frames measures: rasterising is timed apart from presenting (window_target.hpp).
    target.set_stage_timing(o.frames > 0 && !scripted);
    int fbw = 0, fbh = 0;
    window.framebuffer_size(fbw, fbh);
    target.prepare(fbw, fbh);
    ImGuiLayer imgui(ctx, window.handle(), target.render_pass(), target.min_image_count(), target.image_count());
    uint32_t imgui_min_images = target.min_image_count();

    // Live haptics: the mouse device and the servo thread, running from the first frame; the
    // Haptics panel (or `device`, `rate` in a script) switches device and rate later.
    HapticsHost host(servo_core);
    s.haptics = &host;
    s.pose = initial_pose(s.doc.last_valid());
    s.history = PlotHistory(plot_capacity(o.rate));
    {
        const ServoParams params = servo_params_for(s.doc.last_valid(), s.roller, host.watchdog_timeout(), s.roller_travel);
        std::string err = host.start(o.device, o.rate, s.doc.last_valid(), params, s.pose);
        if (!err.empty() && o.device != "mouse") {
            // As a switch from the panel does: say why, and keep the mouse running.
            std::fprintf(stderr, "contactlab edit: --device %s: %s\n", o.device.c_str(), err.c_str());
            s.say("--device " + o.device + ": " + err, true);
            // A device that did not open has already been replaced by the mouse (haptics_host.cpp);
            // a spec that could not be used at all (a bad replay file) has not.
            err = host.servo() != nullptr ? std::string() : host.start("mouse", o.rate, s.doc.last_valid(), params, s.pose);
        }
        if (!err.empty()) std::fprintf(stderr, "contactlab edit: %s\n", err.c_str());
    }
    sync_haptics(s);
    ServoParams published = servo_params_for(s.doc.last_valid(), s.roller, host.watchdog_timeout(), s.roller_travel);
    const drivers::Device* control_said = nullptr;  // the device told that "control" cannot act on it
    std::uint64_t published_revision = s.doc.revision();
    std::uint64_t published_to = host.generation();  // a new servo (device or rate switch) got both at start
    s.camera.resize(target.extent().width, target.extent().height);
    cmd_fit(s);

    // Drawing: the environment of the last valid scene, rebuilt when it changes.
    std::unique_ptr<Environment> env = std::make_unique<Environment>(build_environment(s.doc.last_valid()));
    std::uint64_t env_revision = s.doc.revision();
    // The frame's two draw lists (frame.hpp's layers): the scene under everything, the rest over it.
    render::DrawList scene_list(o.width, o.height), overlay_list(o.width, o.height);
    FrameStages stages;
    s.stages = &stages;
    // The scene layer is rebuilt only when what it shows changes (scene_layer_key.hpp); each new
    // build gets a new cache key, so the window target redraws its kept picture once.
    SceneLayerKey scene_key;
    std::uint64_t scene_cache_key = 0;
    const render::Theme& theme = render::dark_theme();
    FrameTimer timer;
    double window_open_ms = -1.0;
    double last_autosave = 0.0;
    std::optional<ProxyOutput> shown_proxy;  // last frame's, for the status row
    std::uint64_t published_stimulus = ~0ull, published_to_experiment = ~0ull;  // experiment mode
    int exit_code = 0;
    std::string shown_title;
    const Clock::time_point t_loop = Clock::now();

    // The servo's tick records, drained every wake whether or not a frame is drawn: the plots'
    // history, the recording's ring (which must not fill while the editor idles), faults, trials.
    const auto drain_servo = [&] {
        LiveServo& servo = *s.servo;
        servo.reclaim();
        for (drivers::TickRecord r; servo.pop_record(r);) {
            s.history.push(r);
            host.forward(r);
            experiment_on_record(s, r);
            if (r.fault != ServoFault::none) {
                s.last_fault = r.fault;
                s.last_fault_t = r.t;
            }
        }
    };
    // Autosave (recovery file) now and then, drawn or not.
    const auto autosave_now_and_then = [&] {
        if (since(t_loop) - last_autosave > o.autosave_interval) {
            last_autosave = since(t_loop);
            const std::string r = s.doc.autosave();
            if (r.rfind("error: ", 0) == 0) s.say("autosave failed: " + r.substr(7), true);
        }
    };
    RedrawPolicy redraw;
    const auto redraw_inputs = [&](const ServoSnapshot& snap) {
        RedrawInputs in;
        in.events = window.events();
        in.doc_revision = s.doc.revision();
        in.servo_generation = host.generation();
        in.snapshot = &snap;
        in.message = &s.message;
        return in;
    };

    // The frame loop. Should anything throw (a Vulkan error, a full disk), the user's work is
    // written to the recovery file before the error is reported.
    const auto frame_loop = [&] {
        while (!s.quit && !window.should_close()) {
            // Every frame is drawn when measuring (--frames), under a script (but for its `idle`)
            // and in experiments; otherwise only when something changed (redraw_policy.hpp): the
            // loop sleeps until input or kPoll, keeps the servo side drained, and draws if asked.
            const bool on_demand = o.frames <= 0 && !s.experiment && (!scripted || script.idling(since(t_loop)));
            if (on_demand) {
                glfwWaitEventsTimeout(RedrawPolicy::kPoll);
                drain_servo();
                autosave_now_and_then();
                const ServoSnapshot snap = s.servo->snapshot();
                if (!redraw.should_draw(redraw_inputs(snap), since(t_loop))) continue;
            }
            const Clock::time_point t_frame = Clock::now();
            StageTimer events_timer(&stages, Stage::events);
            if (!on_demand) glfwPollEvents();
            events_timer.stop();
            window.framebuffer_size(fbw, fbh);
            if (!target.prepare(fbw, fbh)) {  // minimised: nothing to draw into
                glfwWaitEventsTimeout(0.05);
                continue;
            }
            if (target.min_image_count() != imgui_min_images) {
                imgui_min_images = target.min_image_count();
                imgui.set_min_image_count(imgui_min_images);
            }
            const VkExtent2D ext = target.extent();
            s.camera.resize(static_cast<int>(ext.width), static_cast<int>(ext.height));

            // UI: ImGui frame, then the canvas (real input, or the script's actions).
            StageTimer ui_timer(&stages, Stage::ui);
            imgui.new_frame();
            s.now = since(t_loop);
            if (scripted) {
                script.step(s, since(t_loop));
                if (const auto r = script.take_resize_request()) window.set_size(r->first, r->second);
            }
            else handle_real_input(s, window.handle());
            FrameInfo info;
            info.gpu = ctx.device_name();
            info.present_mode = present_mode_name(target.present_mode());
            info.frame_ms = timer.frame_ms;
            info.fps = timer.fps;
            info.width = static_cast<int>(ext.width);
            info.height = static_cast<int>(ext.height);
            info.validation_messages = ctx.validation_messages();
            draw_panels(s, info, shown_proxy);
            // The fixed parts' px (ImGui units times the framebuffer scale).
            const float ui_scale = ImGui::GetIO().DisplayFramebufferScale.y;
            const EditorLayout layout = current_layout(live_plot_count(s));
            ui_timer.stop();
            StageTimer imgui_timer(&stages, Stage::imgui);
            imgui.render();
            imgui_timer.stop();

            // Title: the file and whether it has unsaved changes.
            const std::string title = "ContactLab editor - " +
                                      (s.doc.path().empty() ? std::string("untitled") : s.doc.path()) +
                                      (s.doc.dirty() ? " *" : "");
            if (title != shown_title) {
                window.set_title(title);
                shown_title = title;
            }

            // Servo: a changed valid scene is published (built here, off the servo thread); Ke, max
            // force and roller gains go as parameters (slew-limited by the servo).
            StageTimer servo_timer(&stages, Stage::servo_sync);
            LiveServo& servo = *s.servo;
            if (published_to != host.generation()) {
                published_to = host.generation();
                published_revision = s.doc.revision();
                published = servo_params_for(s.doc.last_valid(), s.roller, host.watchdog_timeout(), s.roller_travel);
            }
            const bool in_experiment = s.experiment != nullptr;
            if (published_to_experiment != host.generation() && in_experiment) {
                published_to_experiment = host.generation();
                published_stimulus = ~0ull;  // a new servo has the document's scene: send the trial's
            }
            if (in_experiment) {
                // The trial's stimulus, felt and not drawn; nothing while paused.
                if (const std::uint64_t key = experiment_scene_key(s); key != published_stimulus) {
                    servo.publish_scene(experiment_servo_scene(s));
                    published_stimulus = key;
                }
                experiment_scene_published(s, s.now);
            } else if (s.doc.valid() && s.doc.revision() != published_revision) {
                servo.publish_scene(s.doc.scene());
                published_revision = s.doc.revision();
            }
            // Force-only conditions hold the contact element at the pad's centre (1 nm of travel).
            const bool held = in_experiment && experiment.session && !experiment.session->finished() && experiment.session->roller_held();
            const ServoParams params = servo_params_for(in_experiment ? experiment_servo_scene(s) : s.doc.last_valid(), s.roller,
                                                        host.watchdog_timeout(), held ? 1e-9 : s.roller_travel);
            // A scene asking for the passivity controller on a device that declares no effective
            // mass (the mouse, or a scene opened or edited while a device runs): said once per
            // device, never silently run as "fault".
            if (params.passivity != PassivityMode::control) {
                control_said = nullptr;
            } else if (s.device && s.device != control_said) {
                control_said = s.device;
                if (!(drivers::servo_config_for(*s.device, servo.rate()).max_damping > 0.0))
                    s.say(std::string("\"passivity\": \"control\" cannot act on ") + s.device->name() +
                              ": it declares no effective mass, so an energy-generating loop faults as with \"fault\"",
                          true);
            }
            if (!same_params(params, published)) {
                // Refused parameters are said once; the servo keeps the last ones it accepted.
                if (const std::string problem = servo.publish_params(params); !problem.empty())
                    s.say("servo kept its parameters: " + problem, true);

                published = params;
            }
            // The Wearable section's gains, fit mode and FSR noise, to the platform when they differ
            // from its own (a new device starts with the defaults and gets them here).
            if (auto* wd = dynamic_cast<CursorWearableDevice*>(s.device); wd && !(wd->tuning() == s.wearable))
                wd->set_tuning(s.wearable);
            drain_servo();

            servo_timer.stop();

            // Frame: the shared scene drawer, then the editor's marks.
            StageTimer scene_timer(&stages, Stage::scene_geometry);
            if (s.doc.valid() && env_revision != s.doc.revision()) {
                env = std::make_unique<Environment>(build_environment(s.doc.scene()));
                env_revision = s.doc.revision();
            }
            // In an experiment the stimulus is felt, not seen: only the finger is drawn.
            static const Scene hidden;
            static const Environment hidden_env = build_environment(hidden);
            const Scene& shown = s.experiment ? experiment_servo_scene(s) : s.doc.last_valid();
            const ServoSnapshot snap = s.servo->snapshot();
            render::FrameContent content;
            content.scene = s.experiment ? &hidden : &shown;
            content.env = s.experiment ? &hidden_env : env.get();
            ServoSnapshot pose_snap = snap;
            if (snap.ticks == 0) {
                pose_snap.finger = s.pose.finger;
                pose_snap.phi = s.pose.phi;
            }
            content.finger = proxy_output_from(pose_snap, shown.finger);
            content.shape = finger_from_def(shown.finger);
            content.max_force = shown.force.max_force;
            content.overlays = s.overlays;
            content.text = s.labels;
            content.roller_l = snap.roller_l;
            if (const auto* w = dynamic_cast<const CursorWearableDevice*>(s.device)) {
                // Seed 003's platform under the pad, as the simulation has it now.
                const drivers::sim::WearablePlatformView v = w->platform_view();
                if (v.valid) content.platform = render::PlatformDrawing{v.roll, v.press, v.tension, 1.5};
                content.roller_l.reset();  // no roller on the wearable
            }
            content.status_line = false;  // the status row above the rulers shows it (panels.cpp)
            content.top_inset_px = layout.canvas_top * ui_scale;
            content.left_inset_px = layout.canvas_left * ui_scale;
            content.bottom_inset_px = layout.canvas_bottom * ui_scale;
            // The legend's bars between the panel columns: the force-scale bar used to lie under the
            // Plots panel, the length scale bar under the Tuning panel.
            content.left_inset_px = (layout.tuning.right() + kPanelGap) * ui_scale;
            content.right_inset_px = (static_cast<float>(ext.width) / ui_scale - layout.haptics.x + kPanelGap) * ui_scale;
            {
                const render::LegendLayout legend = render::legend_layout(content, s.camera.view());
                const auto ui_rect = [&](const render::PxBox& b) {
                    return Rect{b.x / ui_scale, b.y / ui_scale, b.w / ui_scale, b.h / ui_scale};
                };
                std::vector<PanelPart> bars{{"scale bar", ui_rect(legend.scale_bar)}};
                if (legend.force_bar) bars.push_back({"force-scale bar", ui_rect(*legend.force_bar)});
                if (legend.platform_key) bars.push_back({"platform key", ui_rect(*legend.platform_key)});
                set_canvas_parts(std::move(bars));
            }
            shown_proxy = content.finger;
            const int w = static_cast<int>(ext.width), h = static_cast<int>(ext.height);
            if (scene_list.width() != w || scene_list.height() != h) {
                scene_list = render::DrawList(w, h);
                overlay_list = render::DrawList(w, h);
                scene_key = SceneLayerKey{};
            }
            const render::View view = s.camera.view();
            const SceneLayerKey key = SceneLayerKey::of(s.doc.revision(), s.experiment != nullptr, view, theme);
            const bool follows_finger = render::scene_layer_follows_finger(content);
            if (follows_finger || !(key == scene_key)) {
                scene_list.clear();
                render::build_scene_layer(content, view, theme, scene_list);
                if (!(key == scene_key)) ++scene_cache_key;
                scene_key = key;
            }
            scene_timer.stop();
            StageTimer overlay_timer(&stages, Stage::overlays);
            overlay_list.clear();
            render::build_overlay_layer(content, s.camera.view(), theme, overlay_list);
            draw_canvas_marks(s, theme, overlay_list);
            draw_rulers(s.camera.view(), layout.top_ruler.y * ui_scale, theme, overlay_list);
            overlay_timer.stop();

            // Screenshot: the last of --frames N, or when the script asks.
            std::optional<std::string> shot;
            if (scripted) shot = script.take_screenshot_request();
            else if (o.frames > 0 && timer.frames + 1 == o.frames && !o.screenshot.empty()) shot = o.screenshot;
            render::Image image;
            const WindowTarget::BaseLayer base{&scene_list, follows_finger ? 0 : scene_cache_key};
            const WindowTarget::Layer layers[] = {{&overlay_list, 0}};
            const auto record_imgui = [&](VkCommandBuffer cmd) { imgui.record(cmd); };
            const bool check_layer = scripted && script.take_layer_check_request();
            render::Image kept, fresh;
            FrameOutcome out = target.render(base, layers, theme.background, record_imgui,
                                             shot ? &image : check_layer ? &kept : nullptr, &stages);
            if (out == FrameOutcome::presented && check_layer) {
                // The same frame again with the scene layer drawn in the pass, pixel for pixel.
                out = target.render(WindowTarget::BaseLayer{&scene_list, 0}, layers, theme.background, record_imgui, &fresh);
                if (shot) kept = image;
                s.layer_mismatch = count_differing_pixels(kept, fresh);
            }
            if (out == FrameOutcome::skipped) continue;
            stages.frame_drawn();
            s.scene_layer_updates = target.base_layer_updates();
            redraw.drawn(redraw_inputs(snap), since(t_loop));
            if (shot) {
                render::write_png(*shot, image);
                std::fprintf(stderr, "contactlab edit: screenshot %dx%d written to %s\n", image.width, image.height, shot->c_str());
            }
            if (window_open_ms < 0.0) {
                window_open_ms = 1e3 * since(t_start);
                std::fprintf(stderr, "contactlab edit: window open, first frame presented %.0f ms after start (%s, %s)\n",
                             window_open_ms, ctx.device_name().c_str(), present_mode_name(target.present_mode()));
            }
            timer.add(since(t_frame));

            autosave_now_and_then();

            if (o.frames > 0 && timer.frames >= o.frames && !scripted) break;
            if (scripted && script.finished()) break;
            if (o.timeout > 0.0 && since(t_start) > o.timeout) {
                std::fprintf(stderr, "contactlab edit: still running after --timeout %.0f s; giving up\n", o.timeout);
                exit_code = 1;
                break;
            }
        }
    };
    try {
        frame_loop();
    } catch (...) {
        const std::string r = s.doc.dirty() ? s.doc.autosave() : std::string();
        if (!r.empty()) std::fprintf(stderr, "contactlab edit: unsaved changes kept in %s\n", r.c_str());
        throw;
    }

    // Work not saved goes to the recovery file, never lost silently.
    if (s.doc.dirty()) {
        const std::string r = s.doc.autosave();
        if (!r.empty()) std::fprintf(stderr, "contactlab edit: unsaved changes kept in %s\n", r.c_str());
    }
    if (experiment.session)
        std::fprintf(stderr, "contactlab edit: experiment: %zu of %zu trials recorded in %s\n", experiment.session->done(),
                     experiment.session->total(), experiment.session->results_path().c_str());
    if (host.recording()) cmd_record_stop(s);
    LiveServo& servo = *s.servo;
    servo.stop();
    const double run_s = since(t_loop);
    const auto ps = s.history.period_stats(servo.period());
    std::fprintf(stderr,
                 "contactlab edit: %ld frames in %.2f s at %ux%u: %.2f ms/frame CPU+GPU work, %.1f fps; servo (%s) %.0f Hz "
                 "period p50 %.0f us p99 %.0f us max %.0f us over the last %zu ticks, %llu overruns; %s\n",
                 timer.frames, run_s, target.extent().width, target.extent().height,
                 timer.frames ? 1e3 * timer.busy / timer.frames : 0.0, run_s > 0 ? timer.frames / run_s : 0.0,
                 host.spec().c_str(), host.rate(),
                 ps.p50 * 1e6, ps.p99 * 1e6, ps.max * 1e6, ps.count,
                 static_cast<unsigned long long>(servo.overruns()), servo.scheduling().c_str());
    std::fprintf(stderr, "contactlab edit: frame stages (ms, mean per drawn frame): %s\n", stages.summary().c_str());
    std::fprintf(stderr, "contactlab edit: swapchain recreated %d time(s) (resize, out-of-date, suboptimal)\n",
                 target.recreations());
    if (scripted && script.failures() > 0) {
        std::fprintf(stderr, "contactlab edit: script: %d check(s) failed\n", script.failures());
        exit_code = 1;
    }
    if (ctx.validation_messages() > 0) {
        std::fprintf(stderr, "contactlab edit: %d Vulkan validation message(s)\n", ctx.validation_messages());
        exit_code = 1;
    } else if (o.validation) {
        std::fprintf(stderr, "contactlab edit: validation layers on, 0 messages\n");
    }
    return exit_code;
}

}  // namespace contactlab::editor
