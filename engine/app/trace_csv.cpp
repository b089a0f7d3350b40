// trace_csv.cpp — writing proxy states as CSV (the reader is haptics/finger_samples_csv.cpp).
#include "engine/app/trace_csv.hpp"

#include <cstdio>

namespace contactlab::app {

void write_trace_header(std::FILE* out) { std::fprintf(out, "%s\n", kTraceOutputHeader); }

void write_trace_row(std::FILE* out, double t, const ProxyOutput& o) {
    std::fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, o.finger.x,
                 o.finger.y, o.phi, o.proxy.x, o.proxy.y, o.contact ? 1 : 0, o.depth, o.force.x, o.force.y,
                 o.l_d, o.anchor.x, o.anchor.y);
}

}  // namespace contactlab::app
