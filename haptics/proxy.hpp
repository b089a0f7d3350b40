// proxy.hpp — the virtual finger (god-object proxy) for the arc pad against lines and arcs.
//
// Seed 000 §3: the proxy tracks the finger in free space and stays on the c-space boundary in
// contact. Each update is a constrained motion from the previous proxy toward the measured finger
// centre x_f: straight until a c-space piece is entered, then sliding along it (frictionless)
// toward the nearest point, from piece to piece, until it rests on one piece (one contact) or in
// a corner between two (two contacts). Because the motion is swept, the proxy never crosses a
// feature between ticks, however far the finger jumps. The finger angle phi is driven: when it
// changes, the proxy is first pushed out of the obstacle by at most the distance the pad's ends
// moved (continuous re-projection), then moves as above.
#pragma once

#include "haptics/cspace.hpp"
#include "haptics/environment.hpp"
#include "haptics/finger.hpp"
#include "haptics/stage_clock.hpp"
#include "haptics/validation.hpp"

#include <array>
#include <vector>

namespace contactlab {

struct ProxyDef {
    FingerShape finger;        // pad radius R (m) and length L (m)
    double stiffness = 1000.0; // Ke, N/m: F = Ke (x_fd - x_f), seed 000 eq. 1
    double max_force = 1.5;    // N: |F| is clamped here with its direction kept
    // Several contacts: l_d is their centroid (seed 000) or, with least_displacement, the contact
    // nearest the previous l_d, i.e. the one the roller reaches with the least travel (seed 002).
    ContactRule contact_rule = ContactRule::centroid;
    ForceLaw law;              // spring (Ke above) or ellipsoid; damping; friction cone
    // false: build c-space pieces for every segment of the scene every tick, skipping the
    // bounding-volume tree. Only `contactlab bench` sets it, as the brute-force baseline the
    // index is measured against; results are identical, the cost grows with the scene.
    bool use_index = true;
    // Time the tick's named stages into ProxyOutput::stages (stage_clock.hpp): one clock read per
    // stage, about 0.1 us a tick on the development machine. Off: no clock is read.
    bool profile = false;
    // Free space: at most this many segments' pieces a tick for anticipation's nearest-contact
    // search (0: exact, the whole search every tick). A search that needs more continues in the
    // next ticks, for the finger and angle it started at, and the anticipated contact (l_d, the
    // point) stays the last finished search's until it ends: exact, but late by the ticks it took
    // (ProxyWork::anticipation_behind). Why: 1 cm above a dense valley shaped like the pad, the
    // exact search asks thousands of segments (0.2 ms a tick) for a contact the roller needs only
    // to within its own travel; the bench measures the error against exact.
    int anticipation_budget = 0;
};

inline constexpr double kDefaultServoPeriod = 1e-3;  // s: seed 000's 1 kHz

// The proxy definition (finger, Ke, force clamp, contact rule) a scene asks for.
ProxyDef proxy_def_of(const Scene& scene);

// One contact between the proxy's pad and the contour.
struct ProxyContact {
    Vec2 point{0.0};          // on the contour, m
    double l = 0.0;           // contact location on the pad, m
    int segment = -1;         // EnvSegment index
    CPiece::Source source = CPiece::Source::line_offset;
};

// The work one update did: how tick cost is bounded whatever the input (the extremes suite
// checks these; `contactlab bench` measures the time they take).
inline constexpr int kProxyMaxWalkSteps = 256;       // constrained-motion iterations per tick
inline constexpr int kProxyMaxRotationSteps = 1024;  // finger-angle re-projection sub-steps per tick
// Scenes of at most this many environment segments skip the index: every tick gathers all of them
// (no warm start), which costs less than walking the tree and keeps last tick's pieces.
inline constexpr int kProxySmallScene = 16;
// The most work units (ProxyWork::ahead_units) a tick gives its share of a gather made ahead in
// parts, but for a gather the very next tick needs (its whole query at once); a node's items or a
// segment's build may pass it by a few units. (The tick that takes a gather also finishes what
// the ticks before left: ProxyWork::ahead_rest_units.)
inline constexpr int kProxyAheadMostUnits = 3000;
// The most segments anticipation's search asks while it gathers its hold (Proxy::anticipate):
// beyond, it gives the hold up and prunes as a plain search. Hovering 1 cm above the bench's
// sinusoids, 32 made the slowest ticks of 100 to 1,000-segment scenes ask 30-44 segments where a
// plain search asks 10-24 (p99.9 twice as slow); 8 asks at most 14-24 there and keeps 72-74 % of
// the holds over 100 lines or arcs (42 % over curves).
inline constexpr int kAnticipationHoldAsks = 8;
struct ProxyWork {
    int walk_steps = 0;      // iterations of the constrained motion (<= kProxyMaxWalkSteps)
    int rotation_steps = 0;  // re-projection sub-steps for a change of phi (<= kProxyMaxRotationSteps)
    int segments = 0;        // scene segments gathered near the motion
    int pieces = 0;          // c-space pieces built from them at the final angle
    // Segments whose pieces the motion built afresh this tick (re-projection sub-steps included),
    // rather than copied or kept from the last build at the same angle.
    int built_segments = 0;
    // The warm-start gather about the last proxy sufficed (Proxy::update); false when the full
    // gather about the finger was used (the proxy went further than guessed, or summed forces).
    bool warm_start = false;
    // The warm start's segments were those a recent tick gathered (Proxy::gather_warm), no query.
    bool kept_gather = false;
    // ... or a gather made ahead, when the motion was about to leave the kept one
    // (Proxy::prefetch_gather): its query, and its pieces where the angle held, were made by the
    // ticks before; this one finished what they left.
    bool prefetched_gather = false;
    // Work units (about 12 ns each on the development VM) this tick spent on its share of a gather
    // made ahead in parts (Proxy::prefetch_gather), and at the tick that takes one, on what the
    // ticks before left of it.
    int ahead_units = 0;
    int ahead_rest_units = 0;
    // The walk's first move entered the piece under the resting proxy, found among the pieces
    // near it alone (Proxy::walk), not by a scan along the whole move toward the finger.
    bool near_start = false;
    // Entry scans of the walk answered from the neighbourhood an earlier scan kept (local_), and
    // those that asked every piece's box: sliding along a chain, most of the first.
    int chain_scans = 0;
    int full_scans = 0;
    // Free space: segments whose pieces anticipation's nearest-first search built (Proxy::anticipate).
    int anticipated_segments = 0;
    // Free space with ProxyDef::anticipation_budget: how many ticks ago the search behind this
    // tick's anticipated contact started (0: this tick's own finger and angle), and whether a
    // search is still running. -1: no search has finished since the last contact.
    int anticipation_behind = 0;
    bool anticipation_searching = false;
    // Free space, exact mode: the last search's nearest few segments answered, no search made
    // (Proxy::anticipate's hold: the finger had not moved far enough for another to come nearer).
    bool anticipation_held = false;
    // Free space, exact mode: this tick's search gathered the next ticks' hold, asking up to
    // kAnticipationHoldAsks segments more than a plain search would.
    bool anticipation_gathered = false;
    // The proxy left free space from afar and the gather reached only from where a disc free of
    // pieces let it go straight toward the finger (Proxy::free_advance).
    bool free_advance = false;
};

// Where one update's time went, ns (ProxyDef::profile; all 0 when off). Each stage is the wall
// time of its work in this tick, a warm start redone with the full gather counted in both passes.
struct ProxyStages {
    double gather = 0.0;      // the index's queries: the segments near the motion
    double pieces = 0.0;      // c-space pieces built (or copied) for them, re-projection after a turn
    double walk = 0.0;        // the constrained motion: scans, slides, corners
    double contact = 0.0;     // contacts, exact curve refinement, the force law, l_d
    double anticipate = 0.0;  // free space: the nearest piece and its l_d (seed 000 §3.2)
    double total() const { return gather + pieces + walk + contact + anticipate; }
    ProxyStages& operator+=(const ProxyStages& o) {
        gather += o.gather, pieces += o.pieces, walk += o.walk, contact += o.contact, anticipate += o.anticipate;
        return *this;
    }
};

struct ProxyOutput {
    Vec2 finger{0.0};         // x_f as measured, m
    double phi = 0.0;         // rad
    Vec2 proxy{0.0};          // x_fd, m
    // Where this update moved the proxy from (m): its position at the start of the tick, and
    // after the finger angle's re-projection, before the walk toward the finger. With phi
    // unchanged `turned` is `start`. The servo's energy balance (haptics/energy_balance.hpp)
    // charges the spring energy the turn adds to the hand that turned the finger, and holds the
    // walk (turned -> proxy) to the god-object's promise: it never raises that energy.
    Vec2 start{0.0};
    Vec2 turned{0.0};
    bool contact = false;
    double depth = 0.0;       // |x_fd - x_f| in contact, else 0 (m)
    Vec2 force{0.0};          // on the finger, N (clamped)
    double l_d = 0.0;         // desired contact location (m): centroid of contacts, or anticipated
    int contact_count = 0;
    std::array<ProxyContact, 4> contacts{};
    Vec2 anchor{0.0};         // where the force points: the proxy, or the stiction point (m)
    bool sliding = false;     // friction: the stiction point slid this tick
    // Free space: the c-space piece the finger is nearest to (seed 000 §3.2), if any.
    bool anticipating = false;
    Vec2 anticipated_point{0.0};  // on the contour, m
    ProxyWork work;
    ProxyStages stages;
};

class Proxy {
public:
    // `env` must outlive the proxy (the servo swaps in a new proxy with a new environment).
    Proxy(const Environment& env, const ProxyDef& def);

    // Places the proxy at the finger (no history), e.g. when a device connects.
    void reset(Vec2 finger, double phi);
    // Places the proxy at `proxy` (m) with angle phi (rad), a position remembered from before
    // (the last proxy of a servo being restarted at another rate or on another device, or of the
    // scene before an edit), then pushes it out of any solid it now lies inside by at most
    // `max_push` (m), along the nearest boundary: the least displacement. Allocation-free once
    // the proxy's buffers have grown (the servo calls it in a tick).
    void place(Vec2 proxy, double phi, double max_push);
    // After place(), from the output of the proxy this one replaces (a scene edit): the finger
    // and the motion of its last tick, so the next tick keeps to the warm start like any other,
    // and whether the proxy rests on the surface. Without it, the first tick after an edit saw
    // the whole depth of the press as this tick's motion and gathered every segment within it
    // (0.4-3.5 ms on 100,000 segments under a finger pressed 1-3 cm in). Hints only: the walk's
    // result is the same either way.
    void carry_motion(const ProxyOutput& last);
    // One servo tick: measured finger centre x_f (m) and angle phi (rad); dt (s) since the last
    // tick matters only for damping.
    const ProxyOutput& update(Vec2 finger, double phi, double dt = kDefaultServoPeriod);
    const ProxyOutput& output() const { return out_; }
    const ProxyDef& def() const { return def_; }
    // The built pieces depend on the finger's shape only: a new stiffness, force clamp or force
    // law keeps them. (The servo passes its slewed Ke and clamp every tick; dropping the pieces
    // each time made a 10-segment servo tick cost 3x the proxy's own.)
    void set_def(const ProxyDef& def) {
        if (def.finger != def_.finger) {
            built_valid_ = kept_.valid = pending_.valid = hold_.valid = false;
            ask_cache_size_ = 0;  // the cached pieces were the old finger's
        }
        def_ = def;
    }

private:
    struct Hit {
        bool found = false;
        double s = 2.0;    // path parameter in [0, 1]
        Vec2 point{0.0};
        int piece = -1;
    };
    void gather_for_motion(Vec2 finger, double phi, double reach);
    void gather_within_reach(Vec2 finger, double phi, double reach);  // pieces at phi within reach
    // `out` (segment_ids_, or rotation_ids_ for a turn's sub-steps): segments whose R-offset can
    // come within `reach` of the finger, or that lie within `reach` of the pad's ends between the
    // two angles.
    void gather_near(Vec2 finger, double phi_from, double phi_to, double reach, std::vector<int>& out);
    // A small scene at the angle of the last build (pieces kept) gathers every segment.
    bool gathers_all(double phi_from, double phi_to) const {
        return static_cast<int>(env_->segments.size()) <= kProxySmallScene && phi_from == phi_to && phi_to == built_phi_;
    }
    void build_pieces(double phi);                         // pieces_ of segment_ids_ at phi
    void build_substep_pieces(double phi, const std::vector<int>& ids);  // for a re-projection sub-step
    const PadFrame& pad_frame(double phi);
    struct WarmDisc {
        Vec2 center{0.0};    // m
        double radius = 0.0; // m
    };
    WarmDisc warm_start_disc(Vec2 finger, double max_push) const;
    // The full gather's reach (m) for a free proxy at `start` after its first, piece-free step
    // toward the finger; the plain reach when no such step frees anything.
    double free_advance(Vec2 start, Vec2 finger, double max_push) const;
    // segment_ids_ for a warm start within `warm` as the pad turns by `turn` (rad) to phi: a kept
    // gather when one covers it, else a slightly wider one, kept (kept_).
    WarmDisc gather_warm(const WarmDisc& warm, double phi, double turn);
    void move_proxy(Vec2 finger, double phi, double turn, double max_push, Vec2 start, Vec2 center);
    void note_path(Vec2 p);               // the motion visited p: widen path_extent2_
    void note_path_box(const Aabb& box);  // ... every point of box
    // Pushes the proxy out of the pieces it lies behind by at most max_push (m). With `within`:
    // false, stopping there, when a point it asks the pieces about lies outside that disc.
    bool depenetrate(double max_push, const WarmDisc* within = nullptr);
    bool handed_over(int i, const Vec2& at, const Vec2& t, int ended = -1) const;
    bool inside_or_past_concave_end(const CPiece& piece, double param, double reach) const;
    Vec2 walk(Vec2 from, Vec2 goal);
    // Which pieces first_entry_line asks: those near the motion (from local_ when it holds them
    // all, else from every piece, keeping as local_ those within chain_reach() more), or only
    // those near p (from local_ with among_local, else as full does). The answers near p are the
    // full one only when the hit lies within kLocalAcceptRadius of p: the caller judges.
    enum class Scan { full, among_local, near_start };
    // Where the straight move p -> q first enters a piece.
    Hit first_entry_line(const Vec2& p, const Vec2& q, int exclude_a, int exclude_b, int ended = -1, Scan scan = Scan::full);
    // ... along the circle `on` from parameter s0 to s1 (rad); arc_slide_box_ is then that arc's box.
    Hit first_entry_arc(const CPiece& on, double s0, double s1, int exclude);
    Aabb arc_slide_box_;
    // Whether local_ holds every piece whose box comes within kNearMargin of any point `within`
    // (m) of `at`.
    bool local_near(Vec2 at, double within) const;
    // Whether local_ holds every piece whose box overlaps `box` (m): box lies inside local_box_.
    bool local_holds(const Aabb& box) const;
    // How much wider (m) than its motion a scan keeps local_ (chain walk).
    double chain_reach() const;
    // The entry scans' one loop (first_entry_line, first_entry_arc): ask(i) for the pieces whose
    // boxes overlap `scan` (m), from local_ when it holds them, else from all (keeping local_,
    // further toward the unit direction ahead_of_motion() returns, asked only then, or all round
    // for a zero one).
    template <typename Ask, typename Ahead>
    void scan_pieces(const Aabb& scan, bool from_local, Ask&& ask, Ahead&& ahead_of_motion);
    // Calls visit(i) in order for every piece whose box is not far(box), skipping whole runs and
    // groups whose boxes are; stops when visit returns true.
    template <typename Far, typename Visit>
    void for_pieces(Far&& far, Visit&& visit) const;
    bool try_release_corner(Vec2 goal);
    void collect_contacts(Vec2 goal);
    void refine_on_curves(Vec2 goal);
    void refine_corner();
    void apply_force_law(Vec2 finger, double dt);
    bool contour_leaves_pad_between(int segment_a, int segment_b, Vec2 finger) const;
    double contact_location_of_contacts(double previous_l_d) const;
    void anticipate(Vec2 finger, double phi);

    const Environment* env_;
    ProxyDef def_;
    Vec2 proxy_{0.0};
    Vec2 turned_{0.0};  // m: the proxy after the last move_proxy's re-projection (ProxyOutput::turned)
    double phi_ = 0.0;
    bool initialised_ = false;
    // The last tick ended in contact: the proxy lies on a piece, which the next walk's first move
    // enters at once (walk: asked first of the pieces near the proxy).
    bool resting_ = false;
    int active_[2] = {-1, -1};
    int active_count_ = 0;
    ProxyOutput out_;
    // Scratch space reused every tick (capacity kept: no allocation in steady state).
    std::vector<int> segment_ids_;
    std::vector<int> rotation_ids_;  // move_proxy: the segments near the proxy, for a turn's sub-steps
    std::vector<CPiece> pieces_;
    PadFrame pad_frame_;            // the last pad frame made (pad_frame())
    bool pad_frame_valid_ = false;
    std::vector<Aabb> piece_boxes_;  // each piece's box grown by kBoxSlack: cheap rejection per walk step
    std::vector<Aabb> group_boxes_;  // the box of each run of kPieceGroup consecutive piece_boxes_
    std::vector<Aabb> run_boxes_;    // ... and of each run of kPieceRun
    // What build_pieces last built (pieces_ and piece_boxes_): for segments built_ids_ (sorted)
    // at built_phi_, segment built_ids_[j]'s pieces at [built_first_[j], built_first_[j + 1]).
    // built_valid_ is false once pieces_ holds anything else. next_*: the double buffer.
    std::vector<int> built_ids_, built_first_, next_first_;
    std::vector<CPiece> next_pieces_;
    std::vector<CPiece> nearest_pieces_;  // anticipate: the nearest segment's pieces
    CPiece anticipated_piece_;            // anticipate: the nearest piece
    // anticipate's nearest-first search (spread over ticks with ProxyDef::anticipation_budget):
    // its angle, its best so far (the first piece at the least distance in (segment, piece)
    // order), the tick it started; and the last finished search's answer, published every free
    // tick until the next one ends.
    AabbTree::PadSearch search_;
    double search_phi_ = 0.0;
    int search_best_segment_ = -1;
    Vec2 search_best_foot_{0.0};
    std::int64_t search_started_ = 0;
    std::int64_t ticks_ = 0;
    struct Anticipated {
        bool valid = false;
        double l_d = 0.0;     // m
        Vec2 point{0.0};      // m
        std::int64_t searched_at = 0;
    };
    Anticipated anticipated_;
    // Asks the search for at most `budget` segments (0: all); true when it ended.
    bool continue_anticipation(int budget);
    // The exact distance (m) from the search's finger to segment id's pieces at the search's
    // angle; keeps the nearest (ties: the lowest segment) as the search's best.
    double ask_anticipation(int id);
    // Exact mode's hold (Proxy::anticipate): the last full search's kHeldSegments nearest
    // segments, and a floor (m) under the distance of every other segment's pieces, at that
    // search's finger and angle. A finger that moved m (m) from there, its pad turned so that no
    // pad point moved more than c (m, the turn's chord), has no other segment's piece nearer than
    // floor - m - c (a segment's pieces are where the pad meets it: they move no further than
    // the pad's points, and a distance changes no faster than the finger): when one of the held
    // segments is nearer than that, the nearest of them is the search's answer, bit for bit, and
    // the search is not made.
    static constexpr int kHeldSegments = 3;
    // A hold is asked only while the pad has turned at most this much (rad) from its search's
    // angle (beyond, the chord eats what lead the few segments had over the rest).
    static constexpr double kHoldTurn = 0.05;
    struct AnticipationHold {
        bool valid = false;
        Vec2 finger{0.0};  // m
        double phi = 0.0;  // rad
        std::array<int, kHeldSegments> ids{};
        int count = 0;
        double floor = 0.0;  // m
        int uses = 0;        // ticks it answered
    };
    AnticipationHold hold_;
    int hold_failures_ = 0;  // holds that failed in a row (at most kHoldFailures, proxy.cpp)
    int hold_skip_ = 0;      // free ticks left that search without trying the hold
    // While a search runs: its kHeldSegments + 1 least exact distances (m, ascending) and their
    // segments, and the least bound (m) of the segments it answered by bound or dropped from them.
    std::array<double, kHeldSegments + 1> near_distance_{};
    std::array<int, kHeldSegments + 1> near_segment_{};
    int near_count_ = 0;
    double search_floor_ = 0.0;
    bool collect_hold_ = false;            // this search gathers a hold (exact mode)
    int hold_asks_ = 0;                    // segments it asked for the hold so far
    double hold_motion_ = 0.0;             // m, the finger's motion in the tick before
    void note_hold_failure();             // backs the hold off (hold_skip_)
    double search_best_distance_ = 0.0;    // m, the search's nearest piece so far
    void note_asked(int id, double least);
    // The hold's answer for this finger and angle, if it holds: the search's best (segment, foot,
    // piece) set as a finished search sets them; false (nothing changed) when a search is needed.
    bool held_anticipation(Vec2 finger, double phi);
    // The segment this search asked first (anticipate's seed), -1 if none: when the search
    // reaches it again in its turn, asking it again changes nothing (its pieces and distances are
    // the same, and the best already holds them), so it is not built a second time.
    int search_seed_ = -1;
    // Pieces of the segments anticipation asked recently, at ask_cache_phi_ (rad): a hand
    // hovering without turning asks the same few segments tick after tick, and their pieces
    // depend on the segment and the pad's angle only. Entries index ask_pool_ (capacity fixed
    // when the proxy is made: a full pool starts over, never grows in a tick).
    struct AskedSegment {
        int segment = -1;
        int first = 0;  // in ask_pool_
        int count = 0;
    };
    static constexpr int kAskCache = 16;
    std::array<AskedSegment, kAskCache> ask_cache_{};
    int ask_cache_size_ = 0;
    double ask_cache_phi_ = 0.0;
    std::vector<CPiece> ask_pool_;
    // segment id's pieces at search_phi_, from the cache or built into it.
    const CPiece* asked_pieces(int id, int& count);
    // The first of segment id's pieces (at search_phi_) at the least distance from `finger`: the
    // one a search asking that segment keeps. piece is null for a segment with no pieces.
    struct NearestPiece {
        double distance = 0.0;  // m (+inf without pieces)
        const CPiece* piece = nullptr;
        Vec2 foot{0.0};  // m, the foot of finger on that piece
    };
    NearestPiece nearest_asked_piece(int id, Vec2 finger);
    // The segment nearest p (by distance to the segment itself), -1 in an empty scene.
    int nearest_segment(Vec2 p) const;
    // An empty build keeps the last one here (cache_aside_), still described by built_*.
    std::vector<CPiece> aside_pieces_;
    std::vector<Aabb> aside_boxes_;
    bool cache_aside_ = false;
    std::vector<Aabb> next_boxes_;
    double built_phi_ = 0.0;
    bool built_valid_ = false;
    bool pieces_changed_ = true;  // pieces_ changed since group_boxes_ and run_boxes_ were made
    int contact_pieces_[4] = {-1, -1, -1, -1};  // the piece behind each reported contact
    bool has_stiction_ = false;   // friction: a stiction point is held
    Vec2 stiction_{0.0};          // m
    double previous_depth_ = 0.0; // m, for damping
    ProxyWork work_;              // this tick's, copied into out_
    StageClock clock_;            // ProxyDef::profile
    ProxyStages stages_;          // this tick's, copied into out_
    // The last warm gather, kept for reuse (gather_warm): the segments whose pieces come within
    // disc at any angle in [from, from + width] (rad).
    struct KeptGather {
        std::vector<int> ids;
        WarmDisc disc;
        double from = 0.0, width = 0.0;
        bool valid = false;
    };
    KeptGather kept_;
    // The next tick's kept gather, made ahead where the motion is about to leave kept_.
    KeptGather pending_;
    // Whether g holds every segment a gather of `disc` over the angles [from, from + width] (rad)
    // would: its disc holds the disc and its angles the angles.
    static bool covers(const KeptGather& g, const WarmDisc& disc, double from, double width);
    // The kept gather's disc for a warm disc (gather_warm): a few shortest segments wider, led
    // along the proxy's motion.
    WarmDisc kept_disc_for(const WarmDisc& warm) const;
    void prefetch_gather(const WarmDisc& warm, double phi);
    // The gather made ahead in parts (prefetch_gather), several ticks before the tick that needs
    // it: first its query (ahead_query_), then its segments' pieces at ahead_phi_ (into
    // ahead_pieces_, ahead_boxes_, ahead_first_, as build_pieces makes them), a share of the work
    // each tick; adopt_pending then takes both, finishing what is left. Meaningful while
    // pending_.valid.
    enum class AheadStage { query, build, built };
    AheadStage ahead_stage_ = AheadStage::built;
    AabbTree::PadReach ahead_query_;
    double ahead_phi_ = 0.0;       // rad
    std::size_t ahead_next_ = 0;   // pending_.ids' position the build has reached
    std::int64_t ahead_due_ = 0;   // ticks_ of the tick expected to need it
    int ahead_build_units_ = 0;    // work units (kAheadBuildUnits) left of its build
    std::vector<CPiece> ahead_pieces_;
    std::vector<Aabb> ahead_boxes_;
    std::vector<int> ahead_first_;
    // Does about `units` work units of the gather made ahead (<= 0: all of it); with `build`
    // false, stops after the query.
    void advance_ahead(int units, bool build);
    int ahead_share() const;
    // pending_ becomes kept_ (gather_warm), with the pieces built ahead when they are at phi.
    void adopt_pending(double phi);
    // Appends segment id's pieces at pad (phi) and their boxes: copied from the last build when
    // that was at phi (reuse), else made; j is a cursor in built_ids_ for ids taken in order.
    void append_segment_pieces(int id, const PadFrame& pad, bool reuse, std::size_t& j, std::vector<CPiece>& pieces,
                               std::vector<Aabb>& boxes);
    // gather_near's query, started in q (true), or its answer already in out (false: a small
    // scene or no index); finish_gather sorts what the query appended.
    bool start_gather(Vec2 finger, double phi_from, double phi_to, double reach, AabbTree::PadReach& q,
                      std::vector<int>& out);
    static void finish_gather(std::vector<int>& out);
    double recent_turn_ = 0.0;  // rad, the size of the last tick's turn that was not 0
    std::int64_t last_turn_tick_ = 0;  // ticks_ at that turn
    // Warm start (Proxy::update): the centre of the gathered disc, and the square of how far from it
    // the path went (m^2; path_extent() is the distance, m).
    Vec2 path_center_{0.0};
    double path_extent2_ = 0.0;
    double path_extent() const;
    Vec2 last_finger_{0.0};         // m, the finger at the last tick
    Vec2 last_finger_motion_{0.0};  // m, how the finger moved in the last tick
    Vec2 last_motion_{0.0};         // m, how the proxy moved in the last tick
    // The pieces whose boxes overlapped local_box_ (the last full scan's motion box, grown), in
    // order: questions about points well inside it need ask only these (walk, handed_over).
    std::vector<int> local_;
    Aabb local_box_;
    bool local_valid_ = false;
    // Validation (haptics/validation.hpp): true while update() moves the proxy the slow way (the
    // full gather, every scan over all pieces), the reference its shortcuts are held to.
    bool reference_walk_ = false;
    // Whether the walk may answer from local_: always, unless validation's reference walk runs.
    bool local_scans_allowed() const { return !kValidation || !reference_walk_; }
    // Validation: every segment's pieces searched for the one nearest the finger, as the index's
    // nearest-first search must find it.
    void validate_anticipation(Vec2 finger, const PadFrame& pad, int best_segment, Vec2 best_foot);
};

}  // namespace contactlab
