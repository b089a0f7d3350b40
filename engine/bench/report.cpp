// report.cpp — JSON and Markdown renderings of the bench results (report.hpp).
#include "engine/bench/report.hpp"

#include "engine/bench/goals.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace contactlab::bench {
namespace {

nlohmann::json stats_json(const TickStats& s) {
    return {{"median", s.median_ns}, {"p99", s.p99_ns},       {"p999", s.p999_ns},       {"max", s.max_ns},
            {"ticks", s.ticks},      {"over_100us", s.over_100us}, {"over_1ms", s.over_1ms}};
}

nlohmann::json stages_json(const ProxyStages& st) {
    return {{"gather", st.gather}, {"pieces", st.pieces}, {"walk", st.walk}, {"contact", st.contact}, {"anticipate", st.anticipate}};
}

nlohmann::json tail_json(const TailSplit& t) {
    return {{"ticks", t.ticks}, {"mean_ns", t.mean_ns}, {"stages_ns", stages_json(t.stages)}};
}

// The stage that took most of a set of ticks' time, and its share: "walk 71 %".
std::string main_stage(const ProxyStages& st) {
    const std::pair<const char*, double> all[] = {{"gather", st.gather},   {"pieces", st.pieces},
                                                  {"walk", st.walk},       {"contact", st.contact},
                                                  {"anticipate", st.anticipate}};
    const auto* best = &all[0];
    for (const auto& a : all)
        if (a.second > best->second) best = &a;
    const double total = st.total();
    if (!(total > 0.0)) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s %.0f %%", best->first, 100.0 * best->second / total);
    return buf;
}

const char* cause_name(InstabilityCause c) {
    switch (c) {
        case InstabilityCause::energy: return "energy";
        case InstabilityCause::limit_cycle: return "limit_cycle";
        case InstabilityCause::none: break;
    }
    return "none";
}

std::string metres(double m) {
    if (m == 0.0) return "0";
    if (m < 1e-6) return printf_text("%.2g nm", m * 1e9);
    if (m < 1e-3) return printf_text("%.3g um", m * 1e6);
    return printf_text("%.3g mm", m * 1e3);
}

// The figure under a table: a Markdown image link, or why it is missing.
std::string figure(const ReportPlots* plots, const std::string& file) {
    if (!plots || !plots->skipped.empty()) return "";
    const PlotFile* f = plots->find(file);
    if (!f) return "";
    if (!f->error.empty()) return "\n_Plot `" + file + "` not drawn: " + f->error + "_\n";
    std::string md = "\n![" + f->title + "](" + file + ")\n";
    if (f->skipped_points > 0)
        md += "\n_" + std::to_string(f->skipped_points) +
              " points left out of the plot (not finite, or not positive on a log axis)._\n";
    return md;
}

// How the damping the servo applies compares with the scene's, per rate, from the Z-width rows.
std::string applied_note(const std::vector<ZWidthRow>& rows) {
    std::string off;
    std::vector<double> seen;
    for (const ZWidthRow& z : rows) {
        if (z.damping <= 0.0 || std::find(seen.begin(), seen.end(), z.rate_hz) != seen.end()) continue;
        seen.push_back(z.rate_hz);
        const double ratio = z.damping_applied / z.damping;
        if (std::abs(ratio - 1.0) > 1e-6)
            off += (off.empty() ? "" : ", ") + printf_text("%.3g B", ratio) + printf_text(" at %.0f Hz", z.rate_hz) +
                   printf_text(" (the damper divides the depth's one-tick step by %.3g ms, not by T)", 1e3 / (ratio * z.rate_hz));
    }
    return off.empty() ? "B_a = B at every rate" : "B_a = B except " + off;
}

// One simulated study (study_speed.hpp) as JSON: the run, x real time, ms per s by stage.
nlohmann::json study_json(const StudySpeed& st) {
    if (!st.skipped.empty()) return {{"skipped", st.skipped}};
    const experiments::TrialProfile& p = st.profile;
    const auto per_s = [&](double s) { return p.virtual_s > 0.0 ? 1e3 * s / p.virtual_s : 0.0; };
    nlohmann::json stages;
    for (const experiments::ProfileStage& stage : experiments::kProfileStages) stages[stage.key] = per_s(p.*stage.field);
    stages["all"] = per_s(p.wall);
    return {{"protocol", st.protocol},
            {"trials", p.trials},
            {"virtual_s", p.virtual_s},
            {"wall_s", p.wall},
            {"x_real_time", st.x_real_time()},
            {"rows_time_s", st.rows_time_s},
            {"x_real_time_by_rows", st.x_real_time_by_rows()},
            {"ms_per_virtual_s", stages}};
}

// One simulated study's report section: the title, then the protocol, `how` it ran, its x real
// time, `note`, and the stage table (or why it was skipped).
std::string study_section(const std::string& title, const StudySpeed& st, const std::string& how,
                          const std::string& note) {
    std::string md = "\n## " + title + "\n\n";
    if (!st.skipped.empty()) return md + "Skipped: " + st.skipped + "\n";
    return md + st.protocol + how + printf_text("**%.0fx real time** by the rows' time_s", st.x_real_time_by_rows()) +
           printf_text(" (%.1f s in the rows", st.rows_time_s) +
           printf_text("; %.0fx by the trials' whole virtual time)", st.x_real_time()) + note + experiments::profile_table(st.profile);
}

// The tail twice: every tick's p99.9 and max (the table above, what a user meets on this machine)
// beside the same over each tick's least time across the passes. Every pass replays the same
// stroke, so a tick slow in all passes is slow by its own work and a tick slow in one pass only
// was stalled by the machine; where the two columns differ, the difference is the machine's.
std::string least_of_passes_table(const BenchResults& r) {
    const auto has_least = [](const CostRow& row) { return row.proxy_least && row.hover_least; };
    if (std::none_of(r.cost.begin(), r.cost.end(), has_least)) return "";
    std::string md =
        "\n### The code's tail and the machine's\n\n"
        "Every pass replays the same stroke from the same lifted start, so a tick that is slow in every pass is "
        "slow by its own work, and one slow in a single pass was stalled by the machine (a preemption, an "
        "interrupt, caches flushed by another process). `least of passes`: p99.9 and max over each tick's least "
        "time across the passes. Where it is far below the all-ticks figure, the difference is the machine's "
        "(the machine's own stalls in the same run: the bare loop under \"Servo beside renderer\").\n\n"
        "| scene | N | passes | contact p99.9: all ticks / least of passes | contact max: all / least | hover p99.9: all / "
        "least | hover max: all / least |\n"
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const CostRow& row : r.cost) {
        if (!has_least(row)) continue;
        const TickStats& c = *row.proxy_least;
        const TickStats& h = *row.hover_least;
        md += "| " + row.key + " | " + std::to_string(row.scene.segments) + " | " +
              std::to_string(c.ticks ? row.proxy.ticks / c.ticks : 0) + " | " + duration(row.proxy.p999_ns) + " / " +
              duration(c.p999_ns) + " | " + duration(row.proxy.max_ns) + " / " + duration(c.max_ns) + " | " +
              duration(row.hover.p999_ns) + " / " + duration(h.p999_ns) + " | " + duration(row.hover.max_ns) + " / " +
              duration(h.max_ns) + " |\n";
    }
    return md;
}

// The first tick in contact after a hand's approach (FirstContact), at the largest size.
std::string first_contact_table(const BenchResults& r) {
    const auto has = [](const CostRow& row) { return !row.first_contact.empty(); };
    if (std::none_of(r.cost.begin(), r.cost.end(), has)) return "";
    std::string md = "\n### The first tick in contact, after an approach\n\n"
                     "The strokes above start 3 mm above the profile and press 1 mm in within one tick. A hand comes "
                     "down over many ticks: here the finger descends from " +
                     printf_text("%.0f", kApproachFrom * 1e3) +
                     " mm above the stroke's first sample at each speed (a sample a 1 ms tick), then slides " +
                     std::to_string(kApproachStrokeTicks) +
                     " ticks of the stroke. Each tick's least time over the passes; `after` is the ticks that follow the "
                     "first contact.\n\n"
                     "| scene | N | approach | first contact at tick | its time | after: median / p99.9 / max |\n"
                     "| --- | ---: | ---: | ---: | ---: | ---: |\n";
    for (const CostRow& row : r.cost)
        for (const FirstContact& f : row.first_contact) {
            md += "| " + row.key + " | " + std::to_string(row.scene.segments) + " | " + printf_text("%.2g m/s", f.speed) + " | ";
            md += f.found ? std::to_string(f.tick) + " | " + duration(f.ns) + " | " + duration(f.later.median_ns) + " / " +
                                duration(f.later.p999_ns) + " / " + duration(f.later.max_ns) + " |\n"
                          : std::string("no contact | | |\n");
        }
    return md;
}

}  // namespace

nlohmann::json results_json(const BenchResults& r) {
    nlohmann::json j;
    j["quick"] = r.quick;
    j["units"] = "tick_ns: ns per proxy tick (median, p99, p999, max; over_100us and over_1ms count ticks); "
                 "*_least_of_passes: the same over each tick's least time across the passes; errors in m";
    for (const CostRow& row : r.cost) {
        const std::string n = std::to_string(row.scene.segments);
        j["tick_ns"][row.key][n] = stats_json(row.proxy);
        j["contact_fraction"][row.key][n] = row.contact_fraction;
        j["env_segments"][row.key][n] = row.env_segments;
        j["hover_ns"][row.key][n] = stats_json(row.hover);
        if (row.proxy_least) j["tick_ns_least_of_passes"][row.key][n] = stats_json(*row.proxy_least);
        if (row.hover_least) j["hover_ns_least_of_passes"][row.key][n] = stats_json(*row.hover_least);
        for (const FirstContact& f : row.first_contact) {
            nlohmann::json fc = {{"speed_m_s", f.speed}, {"found", f.found}};
            if (f.found) fc.update({{"tick", f.tick}, {"ns", f.ns}, {"later_ns", stats_json(f.later)}});
            j["first_contact"][row.key][n].push_back(fc);
        }
        if (row.tail_contact.ticks) j["slowest_ticks"][row.key][n] = {{"contact", tail_json(row.tail_contact)}, {"hover", tail_json(row.tail_hover)}};
        if (row.hover_spread) {
            nlohmann::json spread = stats_json(*row.hover_spread);
            spread["segments_per_tick"] = kBenchAnticipationBudget;
            spread["l_d_error_p99_m"] = row.spread_error.l_d_error_p99;
            spread["l_d_error_max_m"] = row.spread_error.l_d_error_max;
            spread["ticks_behind_max"] = row.spread_error.behind_max;
            spread["segments_asked_max"] = row.spread_error.asked_max;
            j["hover_spread_ns"][row.key][n] = spread;
        }
        j["baseline_ns"]["point_finger"][row.key][n] = stats_json(row.point_finger);
        j["ratio_to_baseline"]["point_finger"][row.key][n] = row.proxy.median_ns / row.point_finger.median_ns;
        if (row.brute_force) {
            j["baseline_ns"]["brute_force"][row.key][n] = stats_json(*row.brute_force);
            j["ratio_to_baseline"]["brute_force"][row.key][n] = row.proxy.median_ns / row.brute_force->median_ns;
        }
    }
    for (const FeatureRow& f : r.features)
        j["features"].push_back({{"feature", f.feature}, {"stroke", f.stroke}, {"tick_ns", stats_json(f.stats)}});
    for (const ParetoRow& p : r.pareto) {
        j["pareto"].push_back({{"mode", p.mode},
                               {"tolerance", p.tolerance},
                               {"env_segments", p.env_segments},
                               {"depth_error_max", p.depth_error_max},
                               {"depth_error_p99", p.depth_error_p99},
                               {"proxy_error_max", p.proxy_error_max},
                               {"proxy_error_p99", p.proxy_error_p99},
                               {"tick_ns", stats_json(p.stats)}});
    }
    for (const StabilityRow& s : r.stability) {
        nlohmann::json above = nlohmann::json::array();
        for (const AboveBoundProbe& a : s.above)
            above.push_back({{"ratio", a.ratio},
                             {"outcome", to_string(a.outcome)},
                             {"detect_time", a.detect_time},
                             {"cause", cause_name(a.cause)},
                             {"max_force", a.max_force}});
        j["stability"].push_back({{"rate_hz", s.rate_hz}, {"passivity_bound", s.passivity_bound},
                                  {"passivity_bound_declared", s.bound_declared}, {"b_normal", s.b_normal},
                                  {"b_declared", s.b_declared}, {"k_no_fault", s.k_no_fault},
                                  {"k_settles", s.k_settles}, {"k_ideal_settles", s.k_ideal_settles},
                                  {"k_ideal_no_fault", s.k_ideal_no_fault}, {"above_bound", above}});
    }
    // Z-width (drivers/sim/bench_probes.hpp, ZWidthRow): K in N/m, damping in N s/m; a K equal to
    // search_hi held even there, 0 means not even search_lo held.
    for (const ZWidthRow& z : r.zwidth)
        j["zwidth"].push_back({{"rate_hz", z.rate_hz}, {"damping", z.damping},
                               {"damping_applied", z.damping_applied}, {"k_press", z.k_press},
                               {"k_slide", z.k_slide}, {"k_press_no_fault", z.k_press_no_fault},
                               {"k_slide_no_fault", z.k_slide_no_fault}, {"b_normal", z.b_normal},
                               {"b_declared", z.b_declared}, {"passivity_bound", z.bound_normal},
                               {"passivity_bound_declared", z.bound_declared}, {"search_lo", z.search_lo},
                               {"search_hi", z.search_hi}, {"resolution", z.resolution}});
    // The energy balance on the seeds' trials (energy_table.hpp): J per trial, peaks in J.
    for (const EnergyRow& e : r.energy)
        j["energy_terms"].push_back({{"task", e.task}, {"speed", e.speed}, {"trials", e.trials},
                                     {"hold", e.mean.hold}, {"field", e.mean.field}, {"turn", e.mean.turn},
                                     {"edit", e.mean.edit}, {"proxy", e.mean.proxy}, {"friction", e.mean.friction},
                                     {"damping", e.mean.damping}, {"generated", e.mean.generated()},
                                     {"peak_observer", e.peak_observer}, {"peak_with_turn", e.peak_with_turn},
                                     {"threshold", e.threshold}, {"faulted", e.faulted}, {"would_fault", e.would_fault}});
    // max_error / rms_error: every tick in contact (as before the split); max_tracking_error /
    // rms_tracking_error: outside the jumps of l_d and the window after each (bench_probes.hpp);
    // *_true_*: over those ticks against the true (unquantised) contact location, and
    // max_target_staircase what the encoders' quantisation alone puts into l_d.
    for (const RollerTrackingRow& t : r.roller)
        j["roller_tracking"].push_back({{"gain_scale", t.gain_scale}, {"finger_speed", t.finger_speed},
                                        {"rate_hz", t.rate_hz}, {"feed_forward", t.feed_forward},
                                        {"max_error", t.max_error}, {"rms_error", t.rms_error},
                                        {"max_tracking_error", t.max_tracking_error},
                                        {"rms_tracking_error", t.rms_tracking_error},
                                        {"max_jump_error", t.max_jump_error}, {"jumps", t.jumps},
                                        {"jump_window_s", kJumpSettleWindow},
                                        {"max_true_tracking_error", t.max_true_tracking_error},
                                        {"rms_true_tracking_error", t.rms_true_tracking_error},
                                        {"max_true_encoder_error", t.max_true_encoder_error},
                                        {"max_target_staircase", t.max_target_staircase}});
    for (const RollerJumpRow& t : r.roller_jump)
        j["roller_jump"].push_back({{"jump", t.jump}, {"jump_settle_s", t.jump_settle_s},
                                    {"force_limited_s", t.force_limited_s}, {"band", t.band},
                                    {"overshoot", t.overshoot}, {"max_excursion", t.max_excursion},
                                    {"half_travel", t.half_travel}});
    j["roller_bandwidth_hz"] = r.roller_bandwidth_hz;
    // Frame time in ms (a frame is ~1e6 times a tick: ns would read badly).
    j["render_size"] = {r.render.width, r.render.height};
    j["render_device"] = r.render.device;
    if (!r.render.skipped.empty()) j["render_skipped"] = r.render.skipped;
    for (const RenderFrameRow& row : r.render.rows)
        j["render_ms"][std::to_string(row.segments)] = {{"median", row.frame.median_ns / 1e6},
                                                        {"p99", row.frame.p99_ns / 1e6},
                                                        {"max", row.frame.max_ns / 1e6},
                                                        {"frames", row.frame.ticks},
                                                        {"triangles", row.triangles}};
    // The servo's period (us) alone and beside the renderer (servo_beside_renderer.hpp).
    const ServoBesideRenderer& sb = r.servo_beside;
    if (!sb.skipped.empty()) {
        j["servo_beside_renderer"]["skipped"] = sb.skipped;
    } else {
        auto period = [](const ServoPeriodFigures& f) {
            return nlohmann::json{{"p50_us", f.p50 * 1e6}, {"p99_us", f.p99 * 1e6}, {"max_us", f.max * 1e6},
                                  {"overruns", f.overruns}, {"ticks", f.ticks}};
        };
        j["servo_beside_renderer"] = {{"alone", period(sb.alone)},
                                      {"beside", period(sb.beside)},
                                      {"p99_ratio", sb.alone.p99 > 0.0 ? sb.beside.p99 / sb.alone.p99 : 0.0},
                                      {"rate_10k",
                                       {{"alone", period(sb.alone_10k)},
                                        {"beside", period(sb.beside_10k)},
                                        {"p99_ratio", sb.alone_10k.p99 > 0.0 ? sb.beside_10k.p99 / sb.alone_10k.p99 : 0.0},
                                        {"timer_floor",
                                         {{"late_p50_us", sb.floor_10k.late_p50 * 1e6},
                                          {"late_p99_us", sb.floor_10k.late_p99 * 1e6},
                                          {"late_max_us", sb.floor_10k.late_max * 1e6},
                                          {"missed", sb.floor_10k.missed},
                                          {"ticks", sb.floor_10k.ticks}}}}},
                                      {"fps", sb.fps},
                                      {"device", sb.device},
                                      {"scheduling", sb.scheduling}};
    }
    // The simulated studies' speed (study_speed.hpp): x real time and each stage in ms per s of
    // virtual time; seed 002's against its goal.
    j["simulated_study"] = study_json(r.study);
    if (r.study.skipped.empty()) j["simulated_study"]["goal_x_real_time"] = kStudySpeedGoal;
    j["simulated_study_wearable"] = study_json(r.wearable_study);
    // Each goal's verdict, as the page's "Goals in this run" (goals.hpp).
    j["goals"] = goals_json(judge_goals(r));
    return j;
}

nlohmann::json trace_json(const TraceTiming& t) {
    nlohmann::json j = {{"samples", t.samples}, {"passes", t.passes}, {"contact_fraction", t.contact_fraction},
                        {"tick_ns", stats_json(t.stats)},
                        {"stages_ns", stages_json(t.stages)},
                        {"profiled_tick_ns", stats_json(t.profiled)},
                        {"slowest_ticks", tail_json(t.tail)}};
    if (t.least) j["tick_ns_least_of_passes"] = stats_json(*t.least);
    return j;
}

std::string ticks_csv(const TraceTiming& t) {
    std::string csv = "pass,sample,ns,contact,gather_ns,pieces_ns,walk_ns,contact_ns,anticipate_ns,profiled_ns\n";
    csv.reserve(csv.size() + t.rows.size() * 64);
    char line[256];
    for (const TickRow& r : t.rows) {
        std::snprintf(line, sizeof line, "%d,%zu,%.0f,%d,%.0f,%.0f,%.0f,%.0f,%.0f,%.0f\n", r.pass, r.sample, r.ns, r.contact ? 1 : 0,
                      r.stages.gather, r.stages.pieces, r.stages.walk, r.stages.contact, r.stages.anticipate, r.profiled_ns);
        csv += line;
    }
    return csv;
}

std::string results_markdown(const BenchResults& r, const ReportPlots* plots) {
    std::string md = "# ContactLab bench\n\n";
    md += r.quick ? "A `--quick` run: fewer sizes and ticks; indicative only.\n\n"
                  : "A full run.\n\n";
    if (plots && !plots->skipped.empty())
        md += "**Plots skipped**, Vulkan could not render them: " + plots->skipped +
              "\n\nThe tables hold the same figures.\n\n";
    // The verdicts first: what a user asks of a run is whether the loop fits its period here.
    md += goals_markdown(judge_goals(r));
    md += "## Cost growth: ns per proxy tick\n\n"
          "The finger slides 1 mm deep along the contour (`extent`: 5 mm segments, the contour grows; "
          "`dense`: a 0.4 m sinusoid cut finer). Baselines in the same process: brute force (every "
          "segment every tick, no index) and a point-finger god-object on the same contour; the ratio "
          "is ContactLab's median over the baseline's. `hover`: the same stroke 1 cm above the surface "
          "(free space: the tick anticipates the nearest contact).\n\n"
          "| scene | N | env segments | median | p99 | in contact | brute force (ratio) | point finger (ratio) | hover median / p99 |\n"
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const CostRow& row : r.cost) {
        md += "| " + row.key + " | " + std::to_string(row.scene.segments) + " | " + std::to_string(row.env_segments) +
              " | " + duration(row.proxy.median_ns) + " | " + duration(row.proxy.p99_ns) + " | " +
              printf_text("%.0f %%", 100.0 * row.contact_fraction) + " | " +
              (row.brute_force ? duration(row.brute_force->median_ns) + printf_text(" (%.2f)", row.proxy.median_ns / row.brute_force->median_ns)
                               : std::string("not run")) +
              " | " + duration(row.point_finger.median_ns) + printf_text(" (%.2f)", row.proxy.median_ns / row.point_finger.median_ns) +
              " | " + duration(row.hover.median_ns) + " / " + duration(row.hover.p99_ns) + " |\n";
    }
    md += figure(plots, "cost_extent.png") + figure(plots, "cost_dense.png");
    md += "\n## The tail: the slowest ticks\n\n"
          "A servo is judged by its slowest tick: a late tick holds the last force. p99.9 and max of the same "
          "runs, and the ticks that would miss a 10 kHz period (over 100 us) or a 1 kHz one (over 1 ms). "
          "At the largest size the strokes run again with the proxy's stages timed: `slowest in` is the "
          "stage that took most of the slowest 0.1 % of those ticks.\n\n"
          "| scene | N | contact p99.9 / max | over 100 us / 1 ms | slowest in | hover p99.9 / max | over 100 us / 1 ms | slowest in |\n"
          "| --- | ---: | ---: | ---: | --- | ---: | ---: | --- |\n";
    for (const CostRow& row : r.cost) {
        md += "| " + row.key + " | " + std::to_string(row.scene.segments) + " | " + duration(row.proxy.p999_ns) + " / " +
              duration(row.proxy.max_ns) + " | " + std::to_string(row.proxy.over_100us) + " / " + std::to_string(row.proxy.over_1ms) +
              " of " + std::to_string(row.proxy.ticks) + " | " + (row.tail_contact.ticks ? main_stage(row.tail_contact.stages) : "") +
              " | " + duration(row.hover.p999_ns) + " / " + duration(row.hover.max_ns) + " | " + std::to_string(row.hover.over_100us) +
              " / " + std::to_string(row.hover.over_1ms) + " of " + std::to_string(row.hover.ticks) + " | " +
              (row.tail_hover.ticks ? main_stage(row.tail_hover.stages) : "") + " |\n";
    }
    md += figure(plots, "tail_dense.png");
    md += least_of_passes_table(r);
    md += first_contact_table(r);
    md += "\n## Anticipation spread over ticks (an option)\n\n"
          "Hovering, the tick's work is the search for the contact the finger would make. Over a valley shaped "
          "like the pad, thousands of segments tie to within micrometres and the exact search asks them all. "
          "With the scene's `\"anticipation\": {\"segments_per_tick\": " +
          std::to_string(kBenchAnticipationBudget) +
          "}` a search asks at most that many a tick and continues in the next ones; the anticipated contact "
          "is then the exact one of the tick its search began. The same hover stroke, exact against spread, "
          "and the spread l_d's error against the exact l_d on every free tick (a roller encoder step is 0.04 mm).\n\n"
          "| scene | N | exact p99.9 / max | over 100 us | spread median / p99.9 / max | over 100 us | l_d error p99 / max | answer late by, at most |\n"
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const CostRow& row : r.cost) {
        if (!row.hover_spread) continue;
        md += "| " + row.key + " | " + std::to_string(row.scene.segments) + " | " + duration(row.hover.p999_ns) + " / " +
              duration(row.hover.max_ns) + " | " + std::to_string(row.hover.over_100us) + " of " +
              std::to_string(row.hover.ticks) + " | " + duration(row.hover_spread->median_ns) + " / " +
              duration(row.hover_spread->p999_ns) + " / " + duration(row.hover_spread->max_ns) + " | " +
              std::to_string(row.hover_spread->over_100us) + " of " + std::to_string(row.hover_spread->ticks) + " | " +
              printf_text("%.3g", row.spread_error.l_d_error_p99 * 1e3) + " / " + printf_text("%.3g mm", row.spread_error.l_d_error_max * 1e3) +
              " | " + std::to_string(row.spread_error.behind_max) + " ticks |\n";
    }
    md += "\n## What each feature costs (lines, 1000 segments)\n\n"
          "| feature | stroke | median | p99 |\n| --- | --- | ---: | ---: |\n";
    for (const FeatureRow& f : r.features)
        md += "| " + f.feature + " | " + f.stroke + " | " + duration(f.stats.median_ns) + " | " + duration(f.stats.p99_ns) + " |\n";
    md += "\n## Speed against accuracy (seed 002 bumps, 1 mm deep)\n\n"
          "Errors against exact mode over the stroke; depth error = force error / Ke.\n\n"
          "| mode | tolerance | env segments | median | p99 | depth error p99 / max | proxy error p99 / max |\n"
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const ParetoRow& p : r.pareto) {
        md += "| " + p.mode + " | " + (p.mode == "exact" ? std::string("-") : metres(p.tolerance)) + " | " +
              std::to_string(p.env_segments) + " | " + duration(p.stats.median_ns) + " | " + duration(p.stats.p99_ns) +
              " | " + metres(p.depth_error_p99) + " / " + metres(p.depth_error_max) + " | " + metres(p.proxy_error_p99) +
              " / " + metres(p.proxy_error_max) + " |\n";
    }
    md += figure(plots, "pareto.png");
    md += "\n## Rate against stiffness (closed loop, simulated arm)\n\n"
          "Largest stable Ke (N/m) by bisection next to the discrete passivity bound 2b/T, with b the "
          "arm's damping along the press's normal (`normal`) and the lowest damping the device declares "
          "(`declared`: what the servo knows). Then what a press does at 1.5, 4, 20 and 1000 x the normal "
          "bound: `detected` (instability reported, output zeroed) with the time from first contact and "
          "the detector (E: energy observer, LC: limit cycle), or `bounded bounce` / `at rest` / `runaway` "
          "when not reported.\n\n"
          "| rate | 2b/T normal | 2b/T declared | no fault | settles | ideal arm, settles | 1.5x | 4x | 20x | 1000x |\n"
          "| ---: | ---: | ---: | ---: | ---: | ---: | --- | --- | --- | --- |\n";
    for (const StabilityRow& s : r.stability) {
        md += printf_text("| %.0f Hz", s.rate_hz) + printf_text(" | %.0f", s.passivity_bound) + printf_text(" | %.0f", s.bound_declared) +
              printf_text(" | %.0f", s.k_no_fault) + printf_text(" | %.0f", s.k_settles) + printf_text(" | %.0f", s.k_ideal_settles);
        for (const AboveBoundProbe& a : s.above)
            md += a.outcome == AboveBoundOutcome::detected
                      ? printf_text(" | %.3f s ", a.detect_time) + (a.cause == InstabilityCause::limit_cycle ? "LC" : "E")
                      : std::string(" | ") + to_string(a.outcome);
        md += " |\n";
    }
    md += figure(plots, "stability.png");
    if (!r.zwidth.empty()) {
        md += "\n## Z-width: largest stable K against virtual damping B (closed loop, simulated arm)\n\n"
              "The scene's normal damping B (`force.damping`) against its stiffness K, by bisection (2 %) as "
              "above, pressed 2 mm into the floor and held (`press`) or pressed and stroked 6 cm along it at up "
              "to 0.19 m/s (`slide`), 1 s each. `no fault`: no detector reported, finite, no runaway; `stable`: "
              "also settled (pressed: the force's ripple in the last 0.25 s under 0.1 N or dying; sliding: its "
              "ripple about the 20 ms mean under 0.1 N). B_a: the damping the servo applies per m/s of sampled "
              "normal velocity (" + applied_note(r.zwidth) + "). Against Colgate and Schenkel's "
              "passivity bound 2 (b - |B_a|) / T with b along the normal (and declared), and the first-order "
              "stability limit 2 (b + B_a) / T. `<` : not even the bracket's low end held; `>=`: held at its "
              "top; bound `none`: no K is passive.\n\n"
              "| rate | B | B_a | press: stable | slide: stable | press: no fault | slide: no fault | "
              "2(b_n - B_a)/T | 2(b_d - B_a)/T | 2(b_n + B_a)/T |\n"
              "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
        for (const ZWidthRow& z : r.zwidth) {
            auto k = [&](double v) {
                if (v <= 0.0) return printf_text(" | < %.0f", z.search_lo);
                return (v >= z.search_hi ? std::string(" | >= ") : std::string(" | ")) + printf_text("%.0f", v);
            };
            // <= 0: no K is passive with that much damping applied.
            auto bound = [](double v) { return v > 0.0 ? printf_text(" | %.0f", v) : std::string(" | none"); };
            md += printf_text("| %.0f Hz", z.rate_hz) + printf_text(" | %.2f", z.damping) + printf_text(" | %.3f", z.damping_applied) +
                  k(z.k_press) + k(z.k_slide) + k(z.k_press_no_fault) + k(z.k_slide_no_fault) +
                  bound(z.bound_normal) + bound(z.bound_declared) +
                  printf_text(" | %.0f |\n", 2.0 * (z.b_normal + std::abs(z.damping_applied)) * z.rate_hz);
        }
        md += figure(plots, "zwidth.png");
    }
    if (!r.energy.empty()) {
        md += "\n## Where the energy comes from (the seeds' trials, sim-cld, 1 kHz)\n\n"
              "Each tick's energy balance at the finger (haptics/energy_balance.hpp), summed over a trial and "
              "averaged over the trials, in mJ: `hold` the zero-order hold (K |dx|^2 / 2 a tick), `turn` the "
              "spring energy the hand's turn of the finger put in (not the loop's), `proxy` the god-object's "
              "walk (never positive on lines and arcs), `damping` the device's b along the spring's line. "
              "`generated` = hold + field + proxy + friction + damping is what the observer sums (with a 0.5 s "
              "leak); its peak over the trials against the report threshold, and the peak had `turn` been "
              "counted, as the observer once did.\n\n"
              "| task | speed | trials | hold | turn | proxy | friction | damping | generated | peak | peak with turn | "
              "threshold | faulted | would fault with turn |\n"
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
        for (const EnergyRow& e : r.energy)
            md += "| " + e.task + printf_text(" | %.0f mm/s", e.speed * 1e3) + printf_text(" | %.0f", static_cast<double>(e.trials)) +
                  printf_text(" | %.3f", e.mean.hold * 1e3) + printf_text(" | %.3f", e.mean.turn * 1e3) +
                  printf_text(" | %.3f", e.mean.proxy * 1e3) + printf_text(" | %.3f", e.mean.friction * 1e3) +
                  printf_text(" | %.3f", e.mean.damping * 1e3) + printf_text(" | %.3f", e.mean.generated() * 1e3) +
                  printf_text(" | %.3f", e.peak_observer * 1e3) + printf_text(" | %.3f", e.peak_with_turn * 1e3) +
                  printf_text(" | %.3f", e.threshold * 1e3) + printf_text(" | %.0f", static_cast<double>(e.faulted)) + printf_text(" | %.0f |\n", static_cast<double>(e.would_fault));
    }
    md += printf_text("\n## Roller tracking (seed 000 block task)\n\n"
              "Tracking: |l_d - l| while l_d moves continuously, i.e. outside the jumps of l_d (its 10 ms "
              "mean rate changing by more than %.0f mm/s, or contact made or lost) and the ", kJumpRateChange * 1e3) +
          printf_text("%.0f ms after each; jumps: inside those windows; all: every tick in contact. Feed-forward off is "
              "seed 000's eq. 2 alone (the \"before\"); on is the default (kff = Kd + back-EMF). True: over the "
              "tracking ticks, the contact element (what the finger feels) against l_d from the finger's true, "
              "unquantised pose; staircase: |l_d from the encoders - true l_d| there.\n\n",
              kJumpSettleWindow * 1e3) +
          "| pole scale | feed-forward | finger speed | rate | tracking max | tracking RMS | jumps | jump max | all max | all RMS "
          "| true max | true RMS | staircase max |\n"
          "| ---: | :---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    for (const RollerTrackingRow& t : r.roller)
        md += printf_text("| %.2g", t.gain_scale) + (t.feed_forward ? " | on" : " | off") +
              printf_text(" | %.0f mm/s", t.finger_speed * 1e3) + printf_text(" | %.0f Hz", t.rate_hz) + " | " +
              metres(t.max_tracking_error) + " | " + metres(t.rms_tracking_error) + " | " + std::to_string(t.jumps) +
              " | " + metres(t.max_jump_error) + " | " + metres(t.max_error) + " | " + metres(t.rms_error) + " | " +
              metres(t.max_true_tracking_error) + " | " + metres(t.rms_true_tracking_error) + " | " +
              metres(t.max_target_staircase) + " |\n";
    md += figure(plots, "roller_tracking.png");
    if (!r.roller_jump.empty()) {
        md += "\nRoller alone, a jump of l_d at 1 kHz (default gains): settling into the band, against the least time "
              "the motor's force allows (full drive, then full reverse).\n\n"
              "| jump | settle | force-limited | band | overshoot | furthest from centre / half travel |\n"
              "| ---: | ---: | ---: | ---: | ---: | ---: |\n";
        for (const RollerJumpRow& t : r.roller_jump)
            md += "| " + metres(t.jump) + printf_text(" | %.1f ms", t.jump_settle_s * 1e3) + printf_text(" | %.1f ms", t.force_limited_s * 1e3) +
                  " | " + metres(t.band) + " | " + metres(t.overshoot) + " | " + metres(t.max_excursion) + " / " +
                  metres(t.half_travel) + " |\n";
    }
    md += printf_text("\nRoller 1 cm sine bandwidth (-3 dB, 1 kHz): %.2f Hz (seed 000: about 8 Hz).\n", r.roller_bandwidth_hz);
    md += printf_text("\n## Render frame time (offscreen, %dx%d px)\n\n", r.render.width, r.render.height);
    if (!r.render.skipped.empty()) {
        md += "Skipped: " + r.render.skipped + "\n";
    } else {
        md += "The whole frame: scene -> draw list -> upload, record, submit, wait, read back; the density "
              "case's lines with the finger on them, labels on. Device: " + r.render.device + ".\n\n"
              "| segments | triangles | median | p99 | max | frames |\n| ---: | ---: | ---: | ---: | ---: | ---: |\n";
        for (const RenderFrameRow& row : r.render.rows)
            md += "| " + std::to_string(row.segments) + " | " + std::to_string(row.triangles) + " | " +
                  duration(row.frame.median_ns) + " | " + duration(row.frame.p99_ns) + " | " +
                  duration(row.frame.max_ns) + " | " + std::to_string(row.frame.ticks) + " |\n";
        md += figure(plots, "render_frame.png");
    }
    const ServoBesideRenderer& sb = r.servo_beside;
    md += "\n## Servo beside renderer (1 kHz and 10 kHz, sim-cld block task)\n\n";
    if (!sb.skipped.empty()) {
        md += "Skipped: " + sb.skipped + "\n";
    } else {
        md += printf_text("Each phase %.0f s; servo ", sb.seconds) + sb.scheduling + "; renderer " + sb.device +
              printf_text(", 1280x720 offscreen frames as fast as it goes (%.1f fps) on the other CPUs.\n\n", sb.fps) +
              "| servo | period p50 | p99 | max | overruns / ticks |\n| --- | ---: | ---: | ---: | ---: |\n";
        auto row = [&](const char* name, const ServoPeriodFigures& f) {
            md += std::string("| ") + name + " | " + duration(f.p50 * 1e9) + " | " + duration(f.p99 * 1e9) + " | " +
                  duration(f.max * 1e9) + " | " + std::to_string(f.overruns) + " / " + std::to_string(f.ticks) + " |\n";
        };
        row("1 kHz, alone", sb.alone);
        row("1 kHz, beside the renderer", sb.beside);
        row("10 kHz, alone", sb.alone_10k);
        row("10 kHz, beside the renderer", sb.beside_10k);
        md += "\nThe machine's own floor at 10 kHz, a bare loop waiting as the servo waits on its CPU with nothing "
              "else of ours running: started " + duration(sb.floor_10k.late_p50 * 1e9) + " late at the median, " +
              duration(sb.floor_10k.late_p99 * 1e9) + " at p99, " + duration(sb.floor_10k.late_max * 1e9) + " at most; " +
              std::to_string(sb.floor_10k.missed) + " of " + std::to_string(sb.floor_10k.ticks) +
              " periods a whole period late (overruns no servo on this machine can avoid).\n";
        md += printf_text("\np99 beside / alone: %.3f at 1 kHz, ", sb.alone.p99 > 0.0 ? sb.beside.p99 / sb.alone.p99 : 0.0) +
              printf_text("%.3f at 10 kHz (goal: at most %.1f; at 10 kHz also at most %.0f overrun per 10,000 ticks).\n",
                  sb.alone_10k.p99 > 0.0 ? sb.beside_10k.p99 / sb.alone_10k.p99 : 0.0, kGoalP99Ratio, kGoalExtraOverruns10k);
    }
    md += study_section("Simulated study speed (seed 002, one participant, one core)", r.study,
                        std::string(r.quick ? ", 10 trials per condition (`--quick`)" : ", as shipped") +
                            ", through `experiment run`'s code with `--profile` (no traces): ",
                        printf_text(" (goal: %.0fx).\n\n", kStudySpeedGoal));
    md += study_section("Simulated study speed on the wearable platform (seed 003, one participant, one core)",
                        r.wearable_study,
                        std::string(r.quick ? ", each stimulus once per condition (`--quick`)" : ", as shipped") +
                            ", the same way: ",
                        " (the plant's cable equilibrium is solved every 0.1 ms).\n\n");
    return md;
}

}  // namespace contactlab::bench
