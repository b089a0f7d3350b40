// statistics.cpp — confusion matrices, information transfer, Cramer's phi, t tests
// (statistics.hpp).
#include "engine/experiments/analysis/statistics.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/students_t.hpp>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace contactlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Numbers sort as numbers ("2" < "10"), then other labels as text after them.
bool label_less(const std::string& a, const std::string& b) {
    char* ea = nullptr;
    char* eb = nullptr;
    const double va = std::strtod(a.c_str(), &ea), vb = std::strtod(b.c_str(), &eb);
    const bool na = !a.empty() && *ea == '\0', nb = !b.empty() && *eb == '\0';
    if (na && nb && va != vb) return va < vb;
    if (na != nb) return na;
    return a < b;
}

std::vector<std::string> sorted_unique(std::vector<std::string> v) {
    std::sort(v.begin(), v.end(), label_less);
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
}

std::size_t index_of(const std::vector<std::string>& v, const std::string& s) {
    return static_cast<std::size_t>(std::find(v.begin(), v.end(), s) - v.begin());
}

void undefined(TTest& r, std::string why) {
    r.valid = false;
    r.undefined = std::move(why);
    r.t = r.p = r.ci_low = r.ci_high = kNaN;
}

double largest_magnitude(const std::vector<double>& v, double m = 0.0) {
    for (double x : v) m = std::max(m, std::abs(x));
    return m;
}

double spread(const std::vector<double>& v) {
    if (v.empty()) return 0.0;
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return *hi - *lo;
}

std::string number_text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

// Two-sided p and the half-width of the interval for t with df degrees of freedom.
void finish(TTest& r, double se) {
    if (!(se > 0.0) || !(r.df > 0.0) || !std::isfinite(se)) {
        if (r.undefined.empty()) r.undefined = "no variance";
        r.valid = false;
        r.t = kNaN;
        r.p = kNaN;
        r.ci_low = r.ci_high = kNaN;
        return;
    }
    const boost::math::students_t dist(r.df);
    r.t = r.mean_difference / se;
    r.p = 2.0 * boost::math::cdf(boost::math::complement(dist, std::abs(r.t)));
    const double q = boost::math::quantile(boost::math::complement(dist, 0.5 * (1.0 - r.confidence)));
    r.ci_low = r.mean_difference - q * se;
    r.ci_high = r.mean_difference + q * se;
    r.valid = true;
}

void check_confidence(double c) {
    if (!(c > 0.0 && c < 1.0)) throw std::invalid_argument("confidence must lie in (0, 1)");
}

}  // namespace

long Confusion::total() const {
    long n = 0;
    for (const auto& row : counts)
        for (long v : row) n += v;
    return n;
}

Confusion make_confusion(const std::vector<std::string>& stimuli, const std::vector<std::string>& responses) {
    if (stimuli.size() != responses.size()) throw std::invalid_argument("make_confusion: lists of different lengths");
    Confusion c;
    c.stimuli = sorted_unique(stimuli);
    c.responses = sorted_unique(responses);
    c.counts.assign(c.stimuli.size(), std::vector<long>(c.responses.size(), 0));
    for (std::size_t k = 0; k < stimuli.size(); ++k)
        ++c.counts[index_of(c.stimuli, stimuli[k])][index_of(c.responses, responses[k])];
    return c;
}

double proportion_correct(const Confusion& c) {
    const long n = c.total();
    if (n == 0) return kNaN;
    long right = 0;
    for (std::size_t i = 0; i < c.stimuli.size(); ++i) {
        const std::size_t j = index_of(c.responses, c.stimuli[i]);
        if (j < c.responses.size()) right += c.counts[i][j];
    }
    return static_cast<double>(right) / static_cast<double>(n);
}

double it_est_bits(const Confusion& c) {
    const double n = static_cast<double>(c.total());
    if (n == 0.0) return kNaN;
    std::vector<double> row(c.stimuli.size(), 0.0), col(c.responses.size(), 0.0);
    for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = 0; j < col.size(); ++j) {
            row[i] += static_cast<double>(c.counts[i][j]);
            col[j] += static_cast<double>(c.counts[i][j]);
        }
    double it = 0.0;
    for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = 0; j < col.size(); ++j) {
            const double nij = static_cast<double>(c.counts[i][j]);
            if (nij > 0.0) it += nij / n * std::log2(nij * n / (row[i] * col[j]));
        }
    return it;
}

ChiSquare chi_square(const Confusion& c) {
    std::vector<double> row(c.stimuli.size(), 0.0), col(c.responses.size(), 0.0);
    double n = 0.0;
    for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = 0; j < col.size(); ++j) {
            const double v = static_cast<double>(c.counts[i][j]);
            row[i] += v;
            col[j] += v;
            n += v;
        }
    const auto used = [](const std::vector<double>& m) { return std::count_if(m.begin(), m.end(), [](double v) { return v > 0.0; }); };
    const long r = used(row), k = used(col);
    ChiSquare out;
    if (r < 2 || k < 2) return out;
    for (std::size_t i = 0; i < row.size(); ++i)
        for (std::size_t j = 0; j < col.size(); ++j) {
            if (row[i] == 0.0 || col[j] == 0.0) continue;
            const double expected = row[i] * col[j] / n;
            const double d = static_cast<double>(c.counts[i][j]) - expected;
            out.statistic += d * d / expected;
        }
    out.df = static_cast<double>((r - 1) * (k - 1));
    out.p = boost::math::cdf(boost::math::complement(boost::math::chi_squared(out.df), out.statistic));
    return out;
}

double cramers_phi(const Confusion& c) {
    const double n = static_cast<double>(c.total());
    std::size_t r = 0, k = 0;
    for (std::size_t i = 0; i < c.stimuli.size(); ++i) {
        long s = 0;
        for (long v : c.counts[i]) s += v;
        r += s > 0;
    }
    for (std::size_t j = 0; j < c.responses.size(); ++j) {
        long s = 0;
        for (std::size_t i = 0; i < c.stimuli.size(); ++i) s += c.counts[i][j];
        k += s > 0;
    }
    if (n == 0.0 || r < 2 || k < 2) return 0.0;  // one row or column: nothing can depend on it
    return std::sqrt(chi_square(c).statistic / (n * static_cast<double>(std::min(r, k) - 1)));
}

Summary summarize(const std::vector<double>& x) {
    Summary s;
    s.n = x.size();
    if (x.empty()) {
        s.mean = kNaN;
        return s;
    }
    // Deviations from the first value are exact for values within a factor 2 of it (Sterbenz),
    // so equal values sum to exactly 0 and the mean is exactly their value.
    const double shift = x.front();
    double sum = 0.0;
    for (double v : x) sum += v - shift;
    const double offset = sum / static_cast<double>(x.size());
    s.mean = shift + offset;
    if (x.size() > 1) {
        double ss = 0.0;
        for (double v : x) ss += (v - shift - offset) * (v - shift - offset);
        s.sd = std::sqrt(ss / static_cast<double>(x.size() - 1));
    }
    return s;
}

double roundoff_tolerance(double magnitude) { return 32.0 * std::numeric_limits<double>::epsilon() * magnitude; }

TTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b, double confidence) {
    check_confidence(confidence);
    TTest r;
    r.confidence = confidence;
    r.n_a = a.size();
    r.n_b = b.size();
    const Summary sa = summarize(a), sb = summarize(b);
    r.mean_difference = sa.mean - sb.mean;
    if (a.size() < 2 || b.size() < 2) {
        undefined(r, "fewer than two values in a sample (" + std::to_string(a.size()) + " and " + std::to_string(b.size()) + ")");
        return r;
    }
    const double tol = roundoff_tolerance(largest_magnitude(b, largest_magnitude(a)));
    if (spread(a) <= tol && spread(b) <= tol) {
        undefined(r, "neither sample varies (each within round-off, " + number_text(tol) + ", of one value: " +
                         number_text(sa.mean) + " and " + number_text(sb.mean) + "): t has no variance to compare with");
        return r;
    }
    const double va = sa.sd * sa.sd / static_cast<double>(a.size()), vb = sb.sd * sb.sd / static_cast<double>(b.size());
    const double se = std::sqrt(va + vb);
    r.df = (va + vb) * (va + vb) /
           (va * va / static_cast<double>(a.size() - 1) + vb * vb / static_cast<double>(b.size() - 1));
    finish(r, se);
    return r;
}

TTest paired_t_test(const std::vector<double>& a, const std::vector<double>& b, double confidence) {
    check_confidence(confidence);
    if (a.size() != b.size()) throw std::invalid_argument("paired_t_test: samples of different lengths");
    TTest r;
    r.paired = true;
    r.confidence = confidence;
    r.n_a = r.n_b = a.size();
    std::vector<double> d(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) d[i] = a[i] - b[i];
    const Summary s = summarize(d);
    r.mean_difference = s.mean;
    if (d.size() < 2) {
        undefined(r, "fewer than two pairs (" + std::to_string(d.size()) + ")");
        return r;
    }
    const double tol = roundoff_tolerance(largest_magnitude(b, largest_magnitude(a)));
    if (spread(d) == 0.0) {
        undefined(r, "the differences are all equal (" + number_text(d.front()) + "): t has no variance to compare with");
        return r;
    }
    if (spread(d) <= tol) {
        undefined(r, "the differences are all equal to within round-off (spread " + number_text(spread(d)) + " <= " +
                         number_text(tol) + ", 32 eps times the largest value): t has no variance to compare with");
        return r;
    }
    r.df = static_cast<double>(d.size() - 1);
    finish(r, s.sd / std::sqrt(static_cast<double>(d.size())));
    return r;
}

}  // namespace contactlab::experiments
