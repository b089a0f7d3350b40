// hand_path.cpp — interpolation and the CSV reader for scripted hand paths.
#include "drivers/hand_path.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace contactlab::drivers {

HandPath::HandPath(std::vector<PathSample> samples) : samples_(std::move(samples)) {
    if (samples_.empty()) throw HandPathError("hand path: no samples");
    for (std::size_t i = 1; i < samples_.size(); ++i)
        if (!(samples_[i].t > samples_[i - 1].t)) throw HandPathError("hand path: times must strictly increase");
}

PathPoint HandPath::at(double t) const noexcept {
    const std::size_t n = samples_.size();
    if (n == 0) return {};
    if (!(t > samples_.front().t)) return {samples_.front().x, Vec2{0.0}, samples_.front().phi};
    if (t >= samples_.back().t) return {samples_.back().x, Vec2{0.0}, samples_.back().phi};
    if (cursor_ >= n - 1 || samples_[cursor_].t > t) cursor_ = 0;
    while (cursor_ + 1 < n - 1 && samples_[cursor_ + 1].t <= t) ++cursor_;
    const PathSample& a = samples_[cursor_];
    const PathSample& b = samples_[cursor_ + 1];
    const double dt = b.t - a.t;
    const double u = (t - a.t) / dt;
    return {a.x + (b.x - a.x) * u, (b.x - a.x) / dt, a.phi + (b.phi - a.phi) * u};
}

HandPath read_hand_path_file(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw HandPathError(path + ": cannot open");
    std::string line;
    int line_no = 0;
    std::vector<PathSample> out;
    static const char* kColumns[] = {"t", "x", "y", "phi"};
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line_no == 1) {
            if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
            if (line != "t,x,y,phi") throw HandPathError(path + ":1: expected the header t,x,y,phi");
            continue;
        }
        if (line.empty()) continue;
        double v[4];
        std::stringstream ss(line);
        std::string cell;
        int col = 0;
        while (std::getline(ss, cell, ',')) {
            if (col >= 4) throw HandPathError(path + ":" + std::to_string(line_no) + ": more than 4 columns");
            errno = 0;
            char* end = nullptr;
            v[col] = std::strtod(cell.c_str(), &end);
            if (cell.empty() || end != cell.c_str() + cell.size() || errno == ERANGE || !std::isfinite(v[col]))
                throw HandPathError(path + ":" + std::to_string(line_no) + " (column " + std::to_string(col + 1) +
                                    ", " + kColumns[col] + "): not a finite number: \"" + cell + "\"");
            ++col;
        }
        if (col != 4) throw HandPathError(path + ":" + std::to_string(line_no) + ": expected 4 columns");
        if (!out.empty() && !(v[0] > out.back().t))
            throw HandPathError(path + ":" + std::to_string(line_no) + " (column 1, t): times must strictly increase");
        out.push_back({v[0], {v[1], v[2]}, v[3]});
    }
    if (out.empty()) throw HandPathError(path + ": no samples");
    return HandPath(std::move(out));
}

}  // namespace contactlab::drivers
