// trace_fixture.hpp — writing finger-sample CSVs and running `contactlab trace` on them.
#pragma once

#include "csv.hpp"
#include "process.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace cli_test {

// scenes/flat.json: floor y = 0, solid below; finger R, L; spring Ke; clamp max force.
inline constexpr double kFlatR = 0.026;      // m
inline constexpr double kFlatL = 0.020;      // m
inline constexpr double kFlatKe = 1000.0;    // N/m
inline constexpr double kFlatMaxF = 1.5;     // N
inline constexpr double kTol = 1e-9;

inline constexpr const char* kOutputHeader = "t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d,stiction_x,stiction_y";

struct Sample {
    double t, x, y, phi;
};

// %.17g: reads back to the same double.
inline std::string g17(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

inline std::string samples_csv(const std::vector<Sample>& samples, const char* eol = "\n") {
    std::string text = std::string("t,x,y,phi") + eol;
    for (const Sample& s : samples) text += g17(s.t) + "," + g17(s.x) + "," + g17(s.y) + "," + g17(s.phi) + eol;
    return text;
}

// The finger hangs above the floor at x = 0.01 (free space), descends in three steps to
// `depth` below contact (y = R - depth), then tilts through `phis` (each |R phi| <= L/2).
inline std::vector<Sample> descend_and_tilt(double R, double depth, const std::vector<double>& phis) {
    std::vector<Sample> s;
    double t = 0.0;
    const double x = 0.01;
    for (double y : {R + 0.024, R + 0.014, R + 0.004}) {  // pad bottom at y - R > 0: free
        s.push_back({t, x, y, 0.0});
        t += 0.001;
    }
    s.push_back({t, x, R - depth, 0.0});
    t += 0.001;
    for (double phi : phis) {
        s.push_back({t, x, R - depth, phi});
        t += 0.001;
    }
    return s;
}

inline const std::vector<double>& flat_tilts() {
    static const std::vector<double> phis = {0.1, -0.2, 0.3, -0.38, 0.38, 0.0};  // |0.026*0.38| < 0.01
    return phis;
}

struct TraceRun {
    ProcessResult proc;
    Csv csv;
    bool output_exists = false;
};

// Runs `contactlab trace SCENE --input DIR/in.csv --output DIR/out.csv EXTRA...`.
inline TraceRun run_trace(const TempDir& dir, const std::string& scene_path, const std::string& input_text,
                          const std::vector<std::string>& extra = {}) {
    const std::string in = dir.file("in.csv");
    const std::string out = dir.file("out.csv");
    write_text(in, input_text);
    std::vector<std::string> args = {"trace", scene_path, "--input", in, "--output", out};
    args.insert(args.end(), extra.begin(), extra.end());
    TraceRun r;
    r.proc = run_contactlab(args);
    r.output_exists = fs::exists(out);
    if (r.proc.exit_code == 0 && r.output_exists) r.csv = parse_csv(read_text(out));
    return r;
}

}  // namespace cli_test
