// trace_csv.hpp — the CSV files of `contactlab trace`: finger samples in, proxy states out.
//
// Input:  header `t,x,y,phi`, one sample per line: time (s), finger centre x_f (m), finger angle
//         phi (rad). Times strictly increase.
// Output: header `t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d`, numbers at full precision
//         (%.17g reads back to the same double).
#pragma once

#include "haptics/finger_samples_csv.hpp"
#include "haptics/proxy.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace contactlab::app {

using contactlab::CsvError;
using contactlab::exact;
using contactlab::FingerSample;
using contactlab::read_finger_samples;
using contactlab::read_finger_samples_file;

inline constexpr const char* kTraceInputHeader = kFingerSamplesHeader;
// The first 11 columns are a contract (issue #2); later columns are appended, never reordered:
// stiction_x, stiction_y = the point the force pulls toward (the proxy without friction).
inline constexpr const char* kTraceOutputHeader =
    "t,x,y,phi,proxy_x,proxy_y,contact,depth,fx,fy,l_d,stiction_x,stiction_y";

void write_trace_header(std::FILE* out);
void write_trace_row(std::FILE* out, double t, const ProxyOutput& o);

}  // namespace contactlab::app
