// chai3d_finger_proxy.cpp — times CHAI3D's finger proxy (cAlgorithmFingerProxy) on ContactLab's
// peer workload, so that `contactlab bench --scene peer.json --input peer.csv` has a peer measured
// side by side on the same machine (docs/benchmarks.md, "The peer workload and CHAI3D").
//
// The workload (`contactlab generate peer-workload --segments N -o peer.json --trace peer.csv`):
// a polyline, and finger centres sliding 1 mm deep along it. CHAI3D is 3-D, so the polyline is
// extruded 10 cm along z into a triangle mesh whose normals face free space (+y, the side the
// finger comes from), the proxy is a sphere of the pad's radius (2.6 cm) at the finger centre
// (z = 0, mid-depth), the mesh's collision detector is CHAI3D's AABB tree padded by that radius,
// its stiffness 1000 N/m. Each pass starts the proxy at the first sample (5 cm above the stroke)
// and calls computeForces once per sample, each call timed on its own with the monotonic clock,
// as `contactlab bench` times a tick. Prints the median, p99 and max ns per call over all passes,
// how many samples were in contact, and the finger's depth behind the proxy (|force| / k).
//
// Not part of ContactLab's build (CHAI3D is not a dependency): see CMakeLists.txt here.
#include "chai3d.h"
#include "version.h"  // CHAI3D_VERSION

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Point {
    double x, y;
};

// The peer workload's line segments (peer.json: contours[].segments[] of type "line").
std::vector<std::pair<Point, Point>> read_segments(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    const nlohmann::json j = nlohmann::json::parse(in);
    std::vector<std::pair<Point, Point>> out;
    for (const auto& c : j.at("contours"))
        for (const auto& s : c.at("segments")) {
            if (s.at("type") != "line") throw std::runtime_error(path + ": only line segments are extruded (the peer workload's)");
            out.push_back({{s.at("from")[0], s.at("from")[1]}, {s.at("to")[0], s.at("to")[1]}});
        }
    return out;
}

// The finger centres (peer.csv: t,x,y,phi; phi is 0 throughout: the pad faces down).
std::vector<Point> read_samples(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::string line;
    std::getline(in, line);  // header
    std::vector<Point> out;
    while (std::getline(in, line)) {
        double t, x, y, phi;
        if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &x, &y, &phi) == 4) out.push_back({x, y});
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: %s peer.json peer.csv [passes=20] [radius_m=0.026] [stiffness_n_per_m=1000]\n", argv[0]);
        return 2;
    }
    const int passes = argc > 3 ? std::atoi(argv[3]) : 20;
    const double radius = argc > 4 ? std::atof(argv[4]) : 0.026;     // m, the pad's R
    const double stiffness = argc > 5 ? std::atof(argv[5]) : 1000.0;  // N/m
    const auto segments = read_segments(argv[1]);
    const auto samples = read_samples(argv[2]);
    if (segments.empty() || samples.size() < 2) {
        std::fprintf(stderr, "no segments or samples\n");
        return 2;
    }

    // The polyline extruded over z in [-5, 5] cm: two triangles a segment, wound so that their
    // normals point to the finger's side (+y for a segment running +x).
    chai3d::cWorld* world = new chai3d::cWorld();
    chai3d::cMesh* mesh = new chai3d::cMesh();
    world->addChild(mesh);
    const double half_depth = 0.05;  // m
    for (const auto& [a, b] : segments) {
        const chai3d::cVector3d a0(a.x, a.y, -half_depth), a1(a.x, a.y, half_depth), b0(b.x, b.y, -half_depth),
            b1(b.x, b.y, half_depth);
        mesh->newTriangle(a0, a1, b1);
        mesh->newTriangle(a0, b1, b0);
    }
    mesh->computeAllNormals();
    mesh->m_material->setStiffness(stiffness);
    mesh->createAABBCollisionDetector(radius);
    world->computeGlobalPositions(true);

    chai3d::cAlgorithmFingerProxy proxy;
    std::vector<double> ns;
    ns.reserve(static_cast<std::size_t>(passes) * samples.size());
    std::size_t in_contact = 0;
    std::vector<double> behind;  // m: the finger's depth behind the proxy (|force| / k), first pass, in contact
    for (int pass = 0; pass < passes; ++pass) {
        const chai3d::cVector3d start(samples[0].x, samples[0].y, 0.0);
        proxy.setProxyRadius(radius);
        proxy.initialize(world, start);
        for (const Point& s : samples) {
            const chai3d::cVector3d pos(s.x, s.y, 0.0);
            const auto t0 = std::chrono::steady_clock::now();
            const chai3d::cVector3d f = proxy.computeForces(pos, chai3d::cVector3d(0, 0, 0));
            const auto t1 = std::chrono::steady_clock::now();
            ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count());
            if (pass == 0 && f.length() > 0.0) {
                ++in_contact;
                behind.push_back(f.length() / stiffness);
            }
        }
    }
    std::sort(ns.begin(), ns.end());
    const auto at = [&](double q) { return ns[static_cast<std::size_t>(q * static_cast<double>(ns.size() - 1))]; };
    std::printf("CHAI3D %s cAlgorithmFingerProxy: %zu segments, %zu samples x %d passes, %.0f %% in contact\n", CHAI3D_VERSION,
                segments.size(), samples.size(), passes, 100.0 * static_cast<double>(in_contact) / samples.size());
    std::printf("ns per computeForces: median %.0f, p99 %.0f, max %.0f\n", at(0.5), at(0.99), ns.back());
    if (!behind.empty()) {  // the workload presses 1 mm deep: a proxy on the surface gives about 1 mm
        std::sort(behind.begin(), behind.end());
        std::printf("finger depth behind the proxy in contact (|force| / k): median %.3f mm\n", 1e3 * behind[behind.size() / 2]);
    }
    delete world;
    return 0;
}
