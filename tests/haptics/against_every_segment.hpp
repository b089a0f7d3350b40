// against_every_segment.hpp — replays a hand path through a proxy using the index and through one
// searching every segment (use_index = false), requiring the same proxy, force, l_d and contact
// count on every row, bit for bit: the index and the warm start may only skip pieces that cannot
// matter. Shared by the warm-start and pad-radius tests.
#pragma once

#include "haptics/environment.hpp"
#include "haptics/proxy.hpp"
#include "haptics/verify/random_contact_scenes.hpp"

#include <doctest/doctest.h>

#include <vector>

namespace contactlab::test {

struct AgainstEverySegment {
    int rows = 0;
    int contact_rows = 0;
    int warm_rows = 0;  // in contact, kept by the warm start
    int cold_rows = 0;  // in contact, done again with the full gather
};

inline void replay_against_every_segment(const Environment& env, ProxyDef def,
                                         const std::vector<verify::HandSample>& path, AgainstEverySegment& counts) {
    Proxy indexed(env, def);
    def.use_index = false;
    Proxy brute(env, def);
    indexed.reset(path.front().finger, path.front().phi);
    brute.reset(path.front().finger, path.front().phi);
    for (const verify::HandSample& h : path) {
        const ProxyOutput a = indexed.update(h.finger, h.phi);
        const ProxyOutput& b = brute.update(h.finger, h.phi);
        ++counts.rows;
        REQUIRE(a.proxy == b.proxy);
        REQUIRE(a.force == b.force);
        REQUIRE(a.l_d == b.l_d);
        REQUIRE(a.contact_count == b.contact_count);
        if (!a.contact) continue;
        ++counts.contact_rows;
        (a.work.warm_start ? counts.warm_rows : counts.cold_rows) += 1;
    }
}

}  // namespace contactlab::test
