// test_servo_runner_wait.cpp — how the one deadline loop (drivers/servo_runner.hpp) waits: a
// thread pinned to its own CPU polls the clock for the last part of each wait (a timer wake-up
// comes tens of microseconds late, a quarter of a 10 kHz period), at most half the period; an
// unpinned one only sleeps. What is checked is what the runner reports and that the
// ticks all run; how late wake-ups are is a figure for `contactlab bench` (servo beside renderer,
// 10 kHz row), never a timed unit test.
#include "sim_fixture.hpp"

#include "drivers/servo_runner.hpp"

#include <doctest/doctest.h>

#include <sched.h>

using namespace contactlab;
using namespace contactlab::test;

namespace {

// Runs `ticks` ticks of the block task at `rate` (Hz) in real time; returns the runner's
// scheduling report and checks every tick ran.
std::string run(double rate, int core, long spin_ns, std::uint64_t ticks) {
    Scene scene = load_shipped_scene("block.json");
    drivers::sim::SimCldDevice dev({}, drivers::contour_block_task({}));
    ServoTick servo(drivers::servo_config_for(dev, rate), ServoParams{});
    servo.scenes().publish(std::make_unique<ServoScene>(scene));
    drivers::ServoLoop loop(dev, servo, 1.0 / rate, nullptr);
    REQUIRE(loop.start());
    drivers::RunnerOptions opt;
    opt.core = core;
    opt.spin_ns = spin_ns;
    opt.max_ticks = ticks;
    drivers::ServoRunner runner(loop, opt);
    runner.start();
    runner.join();
    CHECK(runner.ticks() == ticks);
    return runner.scheduling();
}

int some_cpu() {
    cpu_set_t set;
    CPU_ZERO(&set);
    REQUIRE(sched_getaffinity(0, sizeof set, &set) == 0);
    for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &set)) return c;
    return -1;
}

}  // namespace

TEST_CASE("servo runner: a pinned thread polls the last 40 us of each wait, an unpinned one sleeps") {
    const int cpu = some_cpu();
    REQUIRE(cpu >= 0);
    const std::string pinned = run(10000.0, cpu, drivers::RunnerOptions{}.spin_ns, 500);
    CHECK(pinned.find("pinned to CPU " + std::to_string(cpu)) != std::string::npos);
    CHECK(pinned.find("the last 40 us of each wait polled") != std::string::npos);
    const std::string unpinned = run(10000.0, -1, 40000, 500);
    CHECK(unpinned.find("polled") == std::string::npos);
    // Never more than half the period: 50 us at 10 kHz however much is asked.
    CHECK(run(10000.0, cpu, 1000000, 200).find("the last 50 us of each wait polled") != std::string::npos);
    // 0 switches it off.
    CHECK(run(1000.0, cpu, 0, 50).find("polled") == std::string::npos);
}
