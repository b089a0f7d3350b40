// trace_csv.hpp — the CSV files of `contactlab trace`: finger samples in, proxy states out.
//
// Input:  header `t,x,y,phi`, one sample per line: time (s), finger centre x_f (m), finger angle
//         phi (rad). Times strictly increase.
// Output: header `t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d`, numbers at full precision
//         (%.17g reads back to the same double).
#pragma once

#include "haptics/proxy.hpp"

#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace contactlab::app {

// A bad input file: the message names the file, the line and the column.
struct CsvError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct FingerSample {
    double t = 0.0;    // s
    Vec2 x{0.0};       // m
    double phi = 0.0;  // rad
};

inline constexpr const char* kTraceInputHeader = "t,x,y,phi";
inline constexpr const char* kTraceOutputHeader = "t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d";

// Shortest text that reads back to the same double, for messages (std::to_string prints 1e-7
// as "0.000000").
std::string exact(double v);

// Reads samples from `in`; `origin` (the file name) prefixes error messages.
std::vector<FingerSample> read_finger_samples(std::istream& in, const std::string& origin);
std::vector<FingerSample> read_finger_samples_file(const std::string& path);

void write_trace_header(std::FILE* out);
void write_trace_row(std::FILE* out, double t, const ProxyOutput& o);

}  // namespace contactlab::app
