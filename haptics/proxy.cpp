// proxy.cpp — the swept, sliding god-object update (see proxy.hpp for the model).
//
// Index
//   tolerances
//   Proxy::update            one tick: gather pieces, re-project after a phi change, walk, force
//   Proxy::walk              straight motion, sliding along pieces, corners
//   first_entry_line/_arc    where a path first enters the obstacle through some piece
//   collect_contacts         the pieces the final proxy touches and presses against
//   anticipate               free space: l_d from the nearest c-space piece (seed 000 §3.2)
#include "haptics/proxy.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <new>
#include <type_traits>
#include <cmath>

namespace contactlab {
namespace {

// ---- tolerances ---------------------------------------------------------------------------------
// A point within this distance (m) of a piece counts as on it. Far above the rounding of
// coordinates a kilometre from the origin (~1e-13 m), far below any physical scale (1 um).
constexpr double kOnTolerance = 1e-9;
// Sines/cosines below this are "tangential": grazing a piece is not entering it.
constexpr double kTangentTolerance = 1e-12;
// Cosines (between a unit direction of motion and a piece's normal) below this are a graze where
// two pieces meet tangentially (an offset line running into its vertex circle). Moving a distance s
// at such an angle enters by at most s * 1e-9 along a line and r * 1e-18 / 2 into a convex circle:
// far below kOnTolerance for any motion inside the workspace.
constexpr double kGrazeTolerance = 1e-9;

// The graze tolerance for motion against `piece`. A convex circle's normal turns by 1/r per metre,
// so a proxy kOnTolerance away from a tangential junction sees the circle's normal tilted by
// kOnTolerance / r against the line's; moving tangentially into a convex circle at that angle
// enters it by only r * angle^2 / 2.
double graze_tolerance(const CPiece& piece) {
    if (piece.kind == CPiece::Kind::circle && piece.free_outside)
        return std::max(kGrazeTolerance, 4.0 * kOnTolerance / piece.radius);
    return kGrazeTolerance;
}
// Iterations of the constrained motion per tick: each either ends the motion or adds/drops a
// constraint. On ordinary scenes a tick takes 2-5, but sliding over a densely sampled contour
// crosses a vertex every few micrometres (2 iterations each): at 100,000 segments on 0.4 m and
// 5 cm/s that is ~25 per tick, and a cap below that makes the proxy lag and dig in, as if sticky.
// The bound keeps a pathological tick's cost finite.
constexpr int kMaxWalkIterations = kProxyMaxWalkSteps;
constexpr int kMaxDepenetrationIterations = 8;
// A corner push (Proxy::depenetrate) may move the proxy at most this many times the distance the
// pieces moved: a corner whose sides meet at an angle alpha moves by 1 / sin(alpha / 2) times that,
// so this accepts corners sharper than 2 degrees and no phantom crossings far away.
constexpr double kMaxCornerPushFactor = 64.0;
// A turn's sub-steps build only the segments whose pieces come within this many of their pushes
// (each at most the pad end's chord in a sub-step) of the proxy, gathered again every
// kRotationWindow sub-steps (Proxy::move_proxy): a proxy pushed out of a face moves about one
// push a sub-step; corners and thin features can move it further, and then the sub-steps are
// done again with every gathered segment.
constexpr double kRotationNear = 4.0;
constexpr int kRotationWindow = 8;  // sub-steps per gather
// ... unless the window's sub-steps would build at most this many segments (the tick's gather times
// the sub-steps) without it: a query about the proxy costs about what building twenty segments at
// one angle does (seed 002, feel hand: 11,400 instructions a query; ~30 % of them found no fewer
// segments than the tick's own gather).
constexpr int kRotationGatherFrom = 16;
// Free-space anticipation first looks this far (m) beyond the nearest a piece can be: far enough
// that a flat or gently curved surface's nearest piece is found in the first gather.
constexpr double kAnticipationReachMargin = 1e-3;
// Warm start (Proxy::update): the gather about the last proxy reaches at least this far (m), so a
// finger held still or creeping gathers the pieces within a few tens of micrometres...
constexpr double kWarmStartFloor = 2e-5;
// ...and the path must stay this far (m) inside it: far above every tolerance a piece is judged
// with (kOnTolerance, kBoxSlack), far below the distances the proxy moves.
constexpr double kWarmStartMargin = 1e-6;
// A free proxy whose finger moved farther than this (m) in one tick first tries the free-space
// advance (Proxy::free_advance): one nearest-segment query, worth it only for a long move (a
// hand at 0.5 m/s moves 0.5 mm a millisecond; the bench presses 5 cm in one tick).
constexpr double kAdvanceFrom = 1e-3;
// The warm gather is kept for reuse over a disc at most this much wider (m) and a range of angles
// at most this much wider each way (rad; the pad's end moves R times it): Proxy::gather_warm.
constexpr double kMaxKeptReach = 1e-3;
constexpr double kMaxKeptTurn = 1e-2;
// A steady slide re-gathered every tick: the kept disc, centred on the warm one, was only a few
// shortest segments wider, and the proxy moves 50 um a tick at 5 cm/s. It is also led this many
// ticks of the proxy's last motion ahead (Proxy::gather_warm), so the next ticks' discs lie in it.
// (Until the re-gathers were made ahead in parts, the lead stopped where the contour held more
// than 256 segments over the disc: in a valley shaped like the pad a wider disc only made its
// rarer re-gathers slower. Made ahead, a rarer re-gather is spread over more ticks: the dense
// curves' slowest ticks went down with the lead everywhere, and the same strokes took 0.3-2.8 %
// fewer instructions.)
constexpr double kKeptLeadTicks = 2.0;
// ... and only after this many ticks without a turn of the finger.
constexpr std::int64_t kKeptLeadStillTicks = 16;
constexpr int kHoldAsks = kAnticipationHoldAsks;  // (proxy.hpp says why 8)
// A hold that fails backs off for 2^n - 1 ticks after its n-th failure in a row, n at most this.
constexpr int kHoldFailures = 4;
// A kept gather of at least this many segments has the next one made ahead when the motion will
// leave it (Proxy::prefetch_gather)...
constexpr int kPrefetchFrom = 64;
// ... up to this many ticks ahead, its work shared over the ticks before the one expected to need
// it, in units of about 12 ns on the development VM (beside a valley of 100,000 dense curves): a
// node or item the query visits (3), a segment built (16), a segment's pieces copied (1). Each tick
// takes at least kAheadLeastUnits and at most kAheadMostUnits (about 35 us: beside a walk of 20-35
// us in the valley, the tick stays well under 100 us); the query takes the most each tick until it
// ends (its size is not known before), the build what is left over the ticks left.
constexpr int kAheadTicks = 8;
constexpr int kAheadVisitUnits = 3;
constexpr int kAheadBuildUnits = 16;
constexpr int kAheadLeastUnits = 1000;
constexpr int kAheadMostUnits = kProxyAheadMostUnits;
// ... and a turn larger than this (rad) keeps nothing: a kept range stays far below a half-turn,
// where the gather's "shortest way between the two angles" would go round the other way.
constexpr double kMaxKeptTurnSpan = 1.0;
// The walk rejects pieces far from a step by box, first by the box of each run of this many
// consecutive pieces: pieces come in segment order, so a run lies along a few neighbouring
// segments and its box is tight. Sliding over a dense contour a tick takes ~30 steps, each of which
// tested every one of ~200 boxes; a group test skips eight at once. Same pieces, same order: the
// same answers.
constexpr int kPieceGroup = 8;
// ... and before that by the box of each run of this many (kPieceGroup groups): at 20 cm/s over
// 100,000 segments on 0.4 m a tick holds ~350 pieces and a scan tested ~45 group boxes.
constexpr int kPieceRun = 64;
// Scenes of at most this many segments gather all of them every tick: the tree walk cost more
// than the few extra pieces, and the same set each tick keeps last tick's pieces (build_pieces).
// A tenth of a 10-segment scene's tick.
constexpr int kSmallScene = kProxySmallScene;
// Boxes used to reject pieces far from a walk step are grown by this much (m), well beyond every
// tolerance the entry tests accept (kOnTolerance along a piece, t_slack along the motion).
constexpr double kBoxSlack = 1e-8;
// A walk step's scan keeps the pieces whose boxes overlapped its motion box (Proxy::local_). A
// later question about a point J within that box (the slide's end, a corner on it) needs only the
// pieces whose boxes come within kNearMargin (m) of J: every piece a hand-over test at a point
// kLocalAcceptRadius (m) from J looks at. A piece not among them lies more than kBoxSlack +
// kNearMargin from J, so it enters no straight move from J within kLocalAcceptRadius: a hit that
// near is the full scan's too. Why: sliding over a densely sampled contour crosses a vertex every
// few micrometres, and each crossing asked the same questions of all ~200 pieces twice more.
constexpr double kNearMargin = 1e-8;
constexpr double kLocalAcceptRadius = 5e-9;
// Chain walk: a scan of every piece keeps as local_ the pieces within the scene's shortest segment
// (at most kMaxChainReach, m) of its motion, so the slide along the next piece of the chain, which
// ends within that of where this one did, asks those alone. The same pieces are asked, in the
// same order (those whose boxes overlap its motion): the same answer. Over a dense contour the
// walk scanned every piece's box on ~16 slides a tick; now on ~8. (Two shortest segments kept
// more pieces and were no faster.)
constexpr double kMaxChainReach = 1e-4;
// ... and kChainAhead more of it ahead, in the direction the scan's motion goes (Proxy::scan_pieces):
// the walk goes on along the chain that way, so the next slides' boxes stay inside what was kept,
// while kept all round it only added pieces behind and beside. Over 100,000 dense line segments
// the full scans fell from 7.8 to 3.7 a tick and the median tick by 5-9 % (the same answers: the
// kept box only decides which list is asked). 6 did as well, 2 was 4 % slower, 8 and more slower
// (the chain scans then ask 15-36 kept pieces, not 10-15; docs/benchmarks.md, "the kept list ahead").
constexpr double kChainAhead = 4.0;
// A tick whose pieces are the last tick's keeps the last scan's list (local_) if it holds at most
// this many pieces (a dense chain's slide keeps ~15).
constexpr std::size_t kLocalKeptAcrossTicks = 32;
// Sub-steps of a finger-angle change (see Proxy::update): the pad end's chord per sub-step (m) is
// a quarter of the scene's smallest feature, within these bounds, and the count is capped so a
// wild jump of phi costs a bounded time (at the cap a feature thinner than
// 4 * 2R / kMaxRotationSteps ~ 0.2 mm could be crossed by a half-turn jump in one tick).
constexpr double kMinRotationChord = 1e-6;
constexpr double kMaxRotationChord = 2.5e-4;
constexpr int kMaxRotationSteps = kProxyMaxRotationSteps;
// The most pieces append_cspace_pieces makes of one segment: an arc's offset, inner and two pad-end
// circles, each cut by the pad's span into at most two parts (8), and each of its two vertices'
// outer and inner circles, likewise (8). Proxy::asked_pieces keeps room for this many.
constexpr int kMostPiecesPerSegment = 16;

// True when the straight motion from `at` (on the piece) toward `goal` heads into the obstacle
// across this piece. For a line that is "goal behind the line"; for a circle it is not the same as
// "goal inside the circle": a chord toward a goal outside a convex circle still cuts through it.
bool pressing(const CPiece& piece, const Vec2& at, const Vec2& goal) {
    const Vec2 v = goal - at;
    return glm::dot(v, piece_normal_at(piece, at)) < -kTangentTolerance * glm::length(v);
}

// True when `at` is at one end of the piece and moving along direction t takes it off that end:
// the motion cannot enter the piece there, whatever the piece's normal says.
// Motion across the piece's end direction (a cosine within kGrazeTolerance of 0) does not leave:
// sliding along a floor into the foot of a wall must still meet the wall.
bool leaves_range(const CPiece& piece, Vec2 at, Vec2 t) {
    // The direction first: a move along neither way leaves nothing, and a circle's parameter is
    // an arctangent (the same answer, the parameter asked only when it can decide).
    if (piece.kind == CPiece::Kind::line) {
        const double d = glm::dot(t, piece.dir);
        if (d < -kGrazeTolerance) return piece_param(piece, at) <= kOnTolerance;
        if (d > kGrazeTolerance) return piece_param(piece, at) >= piece.len - kOnTolerance;
        return false;
    }
    // Rate of turning about the centre, as a cosine: > 0 is counter-clockwise.
    const double w = cross(glm::normalize(at - piece.center), t);
    const double tol = kOnTolerance / piece.radius;
    if (w < -kGrazeTolerance) return piece_param(piece, at) <= tol;
    if (w > kGrazeTolerance) return piece_param(piece, at) >= piece.span.width - tol;
    return false;
}

Vec2 arc_tangent(const CPiece& piece, double param, double direction) {
    return direction * perp_left(unit_at(piece.span.start + param));
}

// Intersections of the line through p with direction v (|v| > 0) and the circle (c, r):
// parameters t along v. Returns how many (0-2), ascending.
int line_circle(Vec2 p, Vec2 v, Vec2 c, double r, double t[2]) {
    const Vec2 f = p - c;
    const double a = glm::dot(v, v);
    const double b = glm::dot(f, v);
    const double cc = glm::dot(f, f) - r * r;
    const double disc = b * b - a * cc;
    if (disc < 0.0 || a <= 0.0) return 0;
    const double sq = std::sqrt(disc);
    t[0] = (-b - sq) / a;
    t[1] = (-b + sq) / a;
    return 2;
}

// Intersections of circles (c0, r0) and (c1, r1): up to two points.
int circle_circle(Vec2 c0, double r0, Vec2 c1, double r1, Vec2 pts[2]) {
    const Vec2 d = c1 - c0;
    const double dist = glm::length(d);
    if (dist <= 0.0 || dist > r0 + r1 || dist < std::abs(r0 - r1)) return 0;
    const double a = (r0 * r0 - r1 * r1 + dist * dist) / (2.0 * dist);
    const double h = std::sqrt(std::max(0.0, r0 * r0 - a * a));
    const Vec2 u = d / dist;
    const Vec2 m = c0 + a * u;
    pts[0] = m + h * perp_left(u);
    pts[1] = m - h * perp_left(u);
    return 2;
}

// Whether two circle pieces have the same box (piece_box): the same centre, radius and span, bit
// for bit (so a -0 is not a 0).
bool same_circle(const CPiece& a, const CPiece& b) {
    auto same = [](double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); };
    return b.kind == CPiece::Kind::circle && same(a.center.x, b.center.x) && same(a.center.y, b.center.y) &&
           same(a.radius, b.radius) && same(a.span.start, b.span.start) && same(a.span.width, b.span.width);
}

}  // namespace

ProxyDef proxy_def_of(const Scene& scene) {
    ProxyDef def;
    def.finger = finger_from_def(scene.finger);
    def.stiffness = scene.force.stiffness;
    def.max_force = scene.force.max_force;
    def.contact_rule = scene.contact_location.rule;
    def.law = scene.force.law;
    def.anticipation_budget = scene.anticipation.segments_per_tick;
    return def;
}

// Scratch reserved when the proxy is made (off the servo thread: with its ServoScene), so a tick
// never grows it. Small scenes reserve what a tick on them can gather; large ones enough for
// the worst ticks measured on 100,000 segments (a press from 5 cm above gathers about 3,000,
// an edit's place() about 2,000), at most 16,384 segments and pieces (about 8 MB in all).
Proxy::Proxy(const Environment& env, const ProxyDef& def) : env_(&env), def_(def) {
    constexpr std::size_t kMostReserved = 16384;
    const std::size_t n = env.segments.size();
    const std::size_t ids = std::clamp<std::size_t>(n, 1024, kMostReserved);                 // segments
    const std::size_t pieces = std::clamp<std::size_t>(n + n / 2, 4096, kMostReserved);     // pieces
    segment_ids_.reserve(ids);
    rotation_ids_.reserve(ids);
    kept_.ids.reserve(ids);
    pending_.ids.reserve(ids);
    pieces_.reserve(pieces);
    piece_boxes_.reserve(pieces);
    group_boxes_.reserve(pieces / 8 + 1);
    run_boxes_.reserve(pieces / 64 + 1);
    local_.reserve(pieces);
    next_pieces_.reserve(pieces);
    nearest_pieces_.reserve(64);
    ask_pool_.reserve(kAskCache * kMostPiecesPerSegment);

    aside_pieces_.reserve(pieces);
    aside_boxes_.reserve(pieces);
    next_boxes_.reserve(pieces);
    built_ids_.reserve(ids);
    built_first_.reserve(ids + 1);
    next_first_.reserve(ids + 1);
    ahead_pieces_.reserve(pieces);
    ahead_boxes_.reserve(pieces);
    ahead_first_.reserve(ids + 1);
}

void Proxy::reset(Vec2 finger, double phi) {
    proxy_ = finger;
    phi_ = phi;
    initialised_ = true;
    resting_ = false;
    active_count_ = 0;
    last_finger_ = finger;
    last_finger_motion_ = Vec2{0.0};
    last_motion_ = Vec2{0.0};
    search_.active = false;
    anticipated_ = Anticipated{};
}

void Proxy::place(Vec2 proxy, double phi, double max_push) {
    reset(proxy, phi);
    if (!(max_push > 0.0)) return;
    gather_within_reach(proxy, phi, max_push + kOnTolerance);
    build_pieces(phi);
    depenetrate(max_push);
}

// ---- Proxy::update ------------------------------------------------------------------------------
void Proxy::carry_motion(const ProxyOutput& last) {
    if (!is_finite(last.finger) || !is_finite(last.proxy) || !is_finite(last.start)) return;
    last_finger_ = last.finger;
    last_finger_motion_ = Vec2{0.0};
    last_motion_ = last.proxy - last.start;
    resting_ = proxy_ != last.finger;
}

const ProxyOutput& Proxy::update(Vec2 finger, double phi, double dt) {
    if (!initialised_) reset(finger, phi);
    ++ticks_;
    const double previous_l_d = out_.l_d;
    const double R = def_.finger.radius;
    // How far any c-space piece can have moved since the last tick: only pieces made by the pad's
    // ends move with phi, by the chord their end swept. The pad's geometry repeats every 2 pi, so
    // the rotation is the shortest turn between the two angles (a jump from -1e3 to 0.5 rad is a
    // turn of 1000.5 - 159 x 2 pi = 1.49 rad, not 1000.5 rad in a few large sub-steps).
    const double turn = wrap_pi(phi - phi_);  // rad, in [-pi, pi]
    const double dphi = std::abs(turn);
    const double max_push = dphi > 0.0 ? 2.0 * R * std::sin(0.5 * dphi) * (1.0 + 1e-9) + kOnTolerance
                                        : 0.0;
    // Every position the motion can visit lies within |proxy - finger| of the finger, and every
    // piece lies within R of its segment: those segments are all we need (the full gather).
    const double reach = glm::length(proxy_ - finger) + max_push;
    const Vec2 start = proxy_;
    clock_.start(def_.profile);
    work_.kept_gather = false;
    work_.prefetched_gather = false;
    work_.ahead_units = work_.ahead_rest_units = 0;
    work_.built_segments = 0;  // (with validation on, its reference run's builds count too)
    // Validation: the tick the slow way first (every segment within reach, every scan over all
    // pieces), the reference the shortcuts below must match bit for bit.
    Vec2 reference_proxy{0.0};
    if constexpr (kValidation) {
        reference_walk_ = true;
        gather_for_motion(finger, phi, reach + kOnTolerance);
        move_proxy(finger, phi, turn, max_push, start, start);
        reference_walk_ = false;
        reference_proxy = proxy_;
        proxy_ = start;
        clock_.skip();  // not the tick's own work
    }
    stages_ = ProxyStages{};
    work_.warm_start = false;
    // Warm start (contact tracing): the proxy rarely moves far in a tick, so first gather only the
    // pieces near where it is, and move it. The motion's result depends only on pieces within a
    // hair of the path it took (entries along it, pieces through its corners and its end, pushes
    // of at most max_push): if the whole path stayed well inside the gathered disc, every piece
    // left out was irrelevant and the result is the full gather's, bit for bit. Otherwise (the
    // proxy slid further than expected) the tick is done again with the full gather. Under a pad
    // pressed 1 mm into a densely sampled contour this is the few dozen segments the proxy slides
    // over instead of the hundreds within a millimetre of the finger (issue 18).
    // The summed force law looks for every surface the finger has entered (apply_force_law),
    // anywhere within reach: it keeps the full gather.
    // (A small scene gathers everything anyway: nothing to gain, a second walk to lose.)
    const bool local_allowed = def_.use_index && def_.law.contacts != ContactForce::sum && !gathers_all(phi_, phi);
    // Free-space advance: a proxy in free space whose finger went far this tick (a press from
    // above, a jump) first moves straight toward the finger through a disc that holds no piece,
    // so the gather only needs to reach from where that leaves it (see free_advance).
    const double advanced_reach = local_allowed && !resting_ && reach > kAdvanceFrom ? free_advance(start, finger, max_push)
                                                                                      : reach;
    const WarmDisc warm = local_allowed && advanced_reach == reach ? warm_start_disc(finger, max_push)
                                                                   : WarmDisc{start, reach};
    if (warm.radius < reach) {
        const WarmDisc disc = gather_warm(warm, phi, turn);
        clock_.lap(stages_.gather);
        move_proxy(finger, phi, turn, max_push, start, disc.center);
        work_.warm_start = path_extent() + 2.0 * max_push + kWarmStartMargin <= disc.radius;
        if (!work_.warm_start) proxy_ = start;
        if (work_.warm_start && turn == 0.0) {
            prefetch_gather(warm, phi);
            clock_.lap(stages_.gather);
        }
    }
    if (turn != 0.0) {
        recent_turn_ = dphi;
        last_turn_tick_ = ticks_;
    }
    if (!work_.warm_start) {
        work_.free_advance = advanced_reach < reach;
        // A free finger's full gather reaches only as far as it moved and the pad turned: hovering,
        // it finds nothing, tick after tick, and the tree's walk to say so was a fifth of a free
        // tick (seed 002's feel hand hovers a fifth of its ticks). Gathered a little wider and
        // kept (gather_warm), an empty answer also answers the next free ticks whose discs and
        // turns lie inside it: no segment's pieces come near their motion, so the walk is free,
        // as with the segments the full gather's looser bounds may hold (the same walk, bit for
        // bit, as any warm start's). A wider gather that holds segments is not used (building
        // them every turning tick cost more): the full gather is made as before.
        // segment_ids_ left empty when nothing comes within `disc` (m) as the pad turns: a kept
        // gather that covers it and holds no segment, or a new one (gather_warm's, kept).
        auto gather_free = [&](const WarmDisc& disc) {
            const double from = turn == 0.0 ? phi : phi_ + std::min(turn, 0.0);  // rad, as gather_warm's
            const double width = std::abs(turn);                                // rad
            if (width > kMaxKeptTurnSpan) return false;
            if (kept_.ids.empty() && covers(kept_, disc, from, width)) {
                segment_ids_.clear();
                work_.kept_gather = true;
                return true;
            }
            gather_warm(disc, phi, turn);
            return segment_ids_.empty();
        };
        if (!(local_allowed && !resting_ && advanced_reach == reach && gather_free(WarmDisc{finger, reach + kOnTolerance})))
            gather_for_motion(finger, phi, advanced_reach + kOnTolerance);
        clock_.lap(stages_.gather);
        move_proxy(finger, phi, turn, max_push, start, start);
    }
    CONTACTLAB_VALIDATE(proxy_ == reference_proxy,
                        "the warm-start gather and the walk's local scans move the proxy where the full gather and "
                        "full scans do");
    CONTACTLAB_VALIDATE(std::isfinite(proxy_.x) && std::isfinite(proxy_.y), "the proxy is finite");
    CONTACTLAB_VALIDATE(work_.walk_steps <= kProxyMaxWalkSteps && work_.rotation_steps <= kProxyMaxRotationSteps,
                        "a tick's walk and re-projection stay within their step caps");
    last_finger_motion_ = finger - last_finger_;
    last_finger_ = finger;
    last_motion_ = proxy_ - start;
    phi_ = phi;
    // A finger within rounding of the boundary is touching, not pressing: call it free, so that
    // contact does not flicker with the frame's rounding (at 1 km from the origin coordinates
    // carry ~1e-13 m of error; kOnTolerance is 1e-9 m, a force of 1e-6 N at 1000 N/m).
    if (glm::length(proxy_ - finger) <= kOnTolerance) proxy_ = finger;

    // Afresh, in place: a temporary and its copy were a twentieth of a small scene's tick.
    static_assert(std::is_trivially_destructible_v<ProxyOutput>);
    ::new (&out_) ProxyOutput;
    work_.segments = static_cast<int>(segment_ids_.size());
    work_.pieces = static_cast<int>(pieces_.size());
    out_.work = work_;
    out_.finger = finger;
    out_.phi = phi;
    out_.proxy = proxy_;
    out_.start = start;
    out_.turned = turned_;
    resting_ = proxy_ != finger;
    if (resting_) {
        collect_contacts(finger);
        refine_on_curves(finger);  // may move out_.proxy onto the exact curve
        out_.contact = true;
        out_.depth = glm::length(out_.proxy - finger);
        apply_force_law(finger, dt);
        out_.l_d = contact_location_of_contacts(previous_l_d);
        // A contact ends anticipation's search; free again, l_d starts from here.
        search_.active = false;
        anticipated_ = Anticipated{};
        anticipated_.l_d = out_.l_d;
        clock_.lap(stages_.contact);
    } else {
        has_stiction_ = false;
        previous_depth_ = 0.0;
        out_.anchor = finger;
        anticipate(finger, phi);
        clock_.lap(stages_.anticipate);
    }
    out_.stages = stages_;
    CONTACTLAB_VALIDATE(std::isfinite(out_.force.x) && std::isfinite(out_.force.y) && std::isfinite(out_.l_d) &&
                            std::isfinite(out_.depth) && out_.depth >= 0.0,
                        "the proxy's force, depth and l_d are finite, the depth not negative");
    CONTACTLAB_VALIDATE(out_.contact_count >= 0 && out_.contact_count <= static_cast<int>(out_.contacts.size()),
                        "the contact count fits the contact array");
    return out_;
}

// The reach (m) the full gather needs for a proxy at `start` in free space moving toward the
// finger: every piece, at any angle of the pad, lies within R of its segment (offsets, vertex
// circles, pad-end views: cspace.hpp), so none lies within D - R of `start`, D its distance to the
// nearest segment. The walk's first step, straight toward the finger, therefore crosses
// `free` = D - R - margin without meeting a piece (nor does a turn's re-projection push a proxy
// that no piece within max_push holds), and from the point p it reaches every later position lies
// within |p - finger| of the finger, the proxy never moving away from its goal. So the pieces
// within |p - finger| + max_push of the finger are all the walk can meet: the full gather's walk
// bit for bit (validation's reference walk checks it), where reaching from `start` gathered the
// pieces of a disc the size of the jump (a 5 cm press onto 100,000 segments on 0.4 m built
// 25,000 segments' pieces: 3-4 ms in one tick). Returns `reach` unchanged when the bound frees
// nothing (the proxy already within R of the contour).
double Proxy::free_advance(Vec2 start, Vec2 finger, double max_push) const {
    const double R = def_.finger.radius;
    const double to_finger = glm::length(finger - start);  // m
    const double nearest = env_->tree.nearest_distance(
        start, [&](int i) { return distance_to_segment(env_->segments[static_cast<std::size_t>(i)], start); });
    const double free = nearest - R - kWarmStartMargin;  // m, no piece within it of start
    if (!(free > max_push + kWarmStartMargin)) return to_finger + max_push;  // Proxy::update's reach
    return std::max(0.0, to_finger - free) + max_push;
}

// The disc the warm-start gather covers: the proxy is expected to move as it did last tick (it
// slides about as the finger does), so the disc spans that predicted motion from the last proxy,
// with slack of half the motion and of what the finger's own motion changed by, a floor for a
// finger held still, and the pushes of a turn. A guess: a miss costs a second gather, never
// accuracy (Proxy::update checks the path against the disc).
Proxy::WarmDisc Proxy::warm_start_disc(Vec2 finger, double max_push) const {
    const Vec2 finger_motion = finger - last_finger_;  // m, this tick
    const double predicted = glm::length(last_motion_);
    const double slack = 0.5 * std::max(predicted, glm::length(finger_motion)) +
                         glm::length(finger_motion - last_finger_motion_);
    return {proxy_ + 0.5 * last_motion_,
            0.5 * predicted + slack + kWarmStartFloor + 2.0 * max_push + kWarmStartMargin};
}

// segment_ids_ for a warm start within `warm` while the pad turns from phi_ by `turn` (rad), and
// the disc they cover. The gather is made for a slightly wider disc and range of angles than asked
// and kept: while later ticks' discs and turns lie inside them, their segments are the kept ones,
// a superset of the segments their own gather would find. Same pieces near the path, so the same
// walk, bit for bit (validation's reference walk checks it). Why: the tree's query was a tenth of
// a seed 002 participant's time, for segments 2 mm long under a finger moving 50 um a tick.
Proxy::WarmDisc Proxy::gather_warm(const WarmDisc& warm, double phi, double turn) {
    // rad: the turn covers [from, from + |turn|]; without one, the tick's own angle (phi may be
    // phi_ plus whole turns: the pieces are built at phi).
    const double from = turn == 0.0 ? phi : phi_ + std::min(turn, 0.0);
    const double width = std::abs(turn);
    if (width > kMaxKeptTurnSpan) {  // a large turn: gathered as asked, nothing kept
        kept_.valid = false;
        gather_near(warm.center, phi_, phi, warm.radius, segment_ids_);
        return warm;
    }
    if (covers(kept_, warm, from, width)) {
        segment_ids_.assign(kept_.ids.begin(), kept_.ids.end());
        work_.kept_gather = true;
        return kept_.disc;
    }
    // The gather made ahead (prefetch_gather) becomes the kept one: its query, and its pieces
    // where the angle held, were made by the ticks before; adopt_pending finishes the rest.
    if (covers(pending_, warm, from, width)) {
        adopt_pending(phi);
        segment_ids_.assign(kept_.ids.begin(), kept_.ids.end());
        work_.prefetched_gather = true;
        return kept_.disc;
    }
    pending_.valid = false;
    // How much wider: at most two of the scene's shortest segments (so at most two segments more
    // at each side of each strand of contour crossing the disc: a dense contour's walk pays for
    // every piece more). Measured on 100,000 dense curves in contact (least of 3 passes), p99 /
    // p99.9: 1 segment 63 / 119 us, 2: 34 / 134 us, 4: 35 / 159 us, 8: 40 / 190 us. Where a valley
    // crowds the pieces, every re-gather builds the disc's whole ring, so a wider one makes rarer
    // but slower ticks; narrower than 2, more of the p99's ticks re-gather. Also at most
    // four times the warm disc (a handful of ticks of motion), kMaxKeptReach; and twice the last
    // turn each way (a wrist turning steadily), at most kMaxKeptTurn.
    const double margin = std::min(2.0 * recent_turn_, kMaxKeptTurn);  // rad
    kept_.disc = kept_disc_for(warm);
    kept_.from = from - margin;
    kept_.width = width + 2.0 * margin;
    gather_near(kept_.disc.center, kept_.from, kept_.from + kept_.width, kept_.disc.radius, segment_ids_);
    kept_.ids.assign(segment_ids_.begin(), segment_ids_.end());
    kept_.valid = true;
    return kept_.disc;
}

bool Proxy::covers(const KeptGather& g, const WarmDisc& disc, double from, double width) {
    if (!(g.valid && glm::length(disc.center - g.disc.center) + disc.radius <= g.disc.radius)) return false;
    const double offset = wrap_pi(from - g.from);  // rad
    return offset >= 0.0 && offset + width <= g.width;
}

Proxy::WarmDisc Proxy::kept_disc_for(const WarmDisc& warm) const {
    const double extra = std::min({2.0 * env_->min_feature, 4.0 * warm.radius, kMaxKeptReach});  // m
    // Led ahead along the proxy's last motion (kKeptLeadTicks), at most four warm discs or
    // kMaxKeptReach; not at all after an empty or no kept gather (a free finger's: its gathers
    // are kept empty). The disc still holds the warm one: it is widened by the lead.
    Vec2 ahead = kKeptLeadTicks * last_motion_;  // m
    double ahead_cap = 0.0;                      // m
    // Not while the finger turns: every turn builds the kept segments again at the new angle, and
    // a wider gather made seed 002's hand (its angle stepping by encoder counts every few ticks)
    // build 9 % more.
    const bool still = ticks_ - last_turn_tick_ > kKeptLeadStillTicks;
    if (still && kept_.valid && !kept_.ids.empty()) ahead_cap = std::min(4.0 * warm.radius, kMaxKeptReach);
    const double ahead_len = glm::length(ahead);  // m
    if (ahead_len > ahead_cap) ahead = ahead_cap > 0.0 ? ahead * (ahead_cap / ahead_len) : Vec2{0.0};
    return WarmDisc{warm.center + ahead, warm.radius + extra + glm::length(ahead)};
}

// After a warm tick at an unchanged angle: if the warm disc of one of the next kAheadTicks ticks,
// guessed from this one moved by this tick's motion, will not lie in the kept disc, the first such
// tick's gather is made ahead (pending_), for the disc it would make there and this angle: its
// query and then its segments' pieces, a share each tick until that one (advance_ahead); the tick
// that takes it (adopt_pending) finishes what is left. Why: where pieces crowd (a pad in a valley
// of its own shape) a re-gather's query and its builds were each 60-100 us, made in one tick the
// query and in the next the builds: the dense curves' slowest ticks. Nothing here changes which
// segments a tick walks on, only when their query and pieces are made: the same walk, bit for bit.
// A wrong guess costs the work: that tick gathers as before. Only where the last kept gather held
// at least kPrefetchFrom segments: elsewhere a re-gather is cheap.
void Proxy::prefetch_gather(const WarmDisc& warm, double phi) {
    if (pending_.valid && ahead_stage_ != AheadStage::built) {  // under way: this tick's share
        if (phi == ahead_phi_) {
            advance_ahead(ahead_share(), true);
            return;
        }
        pending_.valid = false;  // made for another angle
    }
    if (!kept_.valid || static_cast<int>(kept_.ids.size()) < kPrefetchFrom) return;
    const Vec2 moved = proxy_ - turned_;  // m, this tick's walk
    WarmDisc next{warm.center + moved, warm.radius};
    int ticks = 1;  // until the tick that needs it
    while (covers(kept_, next, phi, 0.0)) {
        if (ticks == kAheadTicks) return;  // the kept gather lasts
        ++ticks;
        next.center += moved;
    }
    if (covers(pending_, next, phi, 0.0)) return;  // made already
    const double margin = std::min(2.0 * recent_turn_, kMaxKeptTurn);  // rad
    pending_.disc = kept_disc_for(next);
    pending_.from = phi - margin;
    pending_.width = 2.0 * margin;
    pending_.valid = true;
    ahead_phi_ = phi;
    ahead_due_ = ticks_ + ticks;
    ahead_next_ = 0;
    ahead_build_units_ = 0;
    ahead_pieces_.clear();
    ahead_boxes_.clear();
    ahead_first_.clear();
    if (!start_gather(pending_.disc.center, pending_.from, pending_.from + pending_.width, pending_.disc.radius, ahead_query_,
                      pending_.ids)) {
        ahead_stage_ = AheadStage::built;  // all of a small scene: nothing to make ahead
        return;
    }
    ahead_stage_ = AheadStage::query;
    // The next tick needs it: the whole query now, its pieces built then (at the angle it has):
    // the query and the builds on two ticks.
    if (ticks == 1) {
        advance_ahead(0, false);
        return;
    }
    advance_ahead(ahead_share(), true);
}

// This tick's share of the gather made ahead (work units): while its query runs, the most (how
// much is left is not known); then what is left of its build over the ticks left before the one
// expected to need it; within [kAheadLeastUnits, kAheadMostUnits].
int Proxy::ahead_share() const {
    if (ahead_stage_ == AheadStage::query) return kAheadMostUnits;
    const std::int64_t left_ticks = std::max<std::int64_t>(1, ahead_due_ - ticks_);
    const std::int64_t left = ahead_build_units_;
    return static_cast<int>(std::clamp<std::int64_t>((left + left_ticks - 1) / left_ticks, kAheadLeastUnits, kAheadMostUnits));
}

void Proxy::advance_ahead(int units, bool build) {
    const bool all = units <= 0;
    int done = 0;  // units this call
    if (ahead_stage_ == AheadStage::query) {
        // (A visit of a node or an item: kAheadVisitUnits units.)
        const int visits = units > 0 ? std::max(1, units / kAheadVisitUnits) : 0;
        int visited = 0;
        const bool ended = env_->tree.continue_pad_reach(ahead_query_, visits, pending_.ids, &visited);
        done += visited * kAheadVisitUnits;
        work_.ahead_units += visited * kAheadVisitUnits;
        if (!ended) return;
        finish_gather(pending_.ids);
        ahead_stage_ = AheadStage::build;
        // The build's units: its segments built at the last build's angle are copied.
        const bool reuse = built_valid_ && built_phi_ == ahead_phi_;
        std::size_t copied = 0, k = 0;
        if (reuse)
            for (const int id : pending_.ids) {
                while (k < built_ids_.size() && built_ids_[k] < id) ++k;
                if (k < built_ids_.size() && built_ids_[k] == id) ++copied;
            }
        ahead_build_units_ = static_cast<int>(copied + (pending_.ids.size() - copied) * kAheadBuildUnits);
        if (!all) {
            units -= done;
            if (units <= 0) return;  // this call's share spent
        }
    }
    if (ahead_stage_ == AheadStage::build && build) {
        // Copied from the last build when it was at this angle; a cursor into it per call (a
        // build between calls, validation's reference walk's, may have changed it).
        const bool reuse = built_valid_ && built_phi_ == ahead_phi_;
        const PadFrame& pad = pad_frame(ahead_phi_);
        std::size_t j = 0;
        if (built_valid_ && ahead_next_ < pending_.ids.size())
            j = static_cast<std::size_t>(std::lower_bound(built_ids_.begin(), built_ids_.end(), pending_.ids[ahead_next_]) -
                                         built_ids_.begin());
        int spent = 0;
        while (ahead_next_ < pending_.ids.size()) {
            if (!all && spent >= units) break;
            const int built_before = work_.built_segments;
            ahead_first_.push_back(static_cast<int>(ahead_pieces_.size()));
            append_segment_pieces(pending_.ids[ahead_next_], pad, reuse, j, ahead_pieces_, ahead_boxes_);
            spent += work_.built_segments > built_before ? kAheadBuildUnits : 1;
            ++ahead_next_;
        }
        ahead_build_units_ = std::max(0, ahead_build_units_ - spent);
        work_.ahead_units += spent;
        if (ahead_next_ == pending_.ids.size()) {
            ahead_first_.push_back(static_cast<int>(ahead_pieces_.size()));
            ahead_stage_ = AheadStage::built;
        }
    }
}

void Proxy::adopt_pending(double phi) {
    // What the ticks before did not finish: the rest of the query, and of the build if it is at
    // this angle (else build_pieces builds them as for any gather).
    const bool at_phi = phi == ahead_phi_;
    if (ahead_stage_ != AheadStage::built) {
        const int shares = work_.ahead_units;
        advance_ahead(0, at_phi);
        work_.ahead_rest_units = work_.ahead_units - shares;
        work_.ahead_units = shares;
    }
    std::swap(kept_, pending_);
    pending_.valid = false;
    if (!at_phi || ahead_first_.empty()) return;
    std::swap(pieces_, ahead_pieces_);
    std::swap(piece_boxes_, ahead_boxes_);
    std::swap(built_first_, ahead_first_);
    built_ids_.assign(kept_.ids.begin(), kept_.ids.end());
    built_phi_ = phi;
    built_valid_ = true;
    cache_aside_ = false;
    pieces_changed_ = true;
    local_valid_ = false;
    active_count_ = 0;
    ahead_first_.clear();
}

// Turns the pad from phi_ to phi (re-projecting) and walks the proxy from `start` toward the
// finger, on the pieces of segment_ids_; path_extent() is how far from `center` the path went.
void Proxy::move_proxy(Vec2 finger, double phi, double turn, double max_push, Vec2 start, Vec2 center) {
    const double R = def_.finger.radius;
    const double dphi = std::abs(turn);
    path_center_ = center;
    path_extent2_ = 0.0;
    proxy_ = start;
    // Re-project continuously: rotate in sub-steps whose pad-end chord is at most a quarter of
    // the scene's smallest feature, pushing the proxy out after each. A push is only ever as deep
    // as one sub-step's chord, so it always exits through the face the pad was touching and never
    // through the far side of a thin wall (which a single large rotation could reach).
    if (max_push > 0.0) {
        const double chord_step = std::clamp(0.25 * env_->min_feature, kMinRotationChord, kMaxRotationChord);
        const int steps = std::clamp(static_cast<int>(std::ceil(max_push / chord_step)), 1, kMaxRotationSteps);
        const double sub_push = 2.0 * R * std::sin(0.5 * dphi / steps) * (1.0 + 1e-9) + kOnTolerance;
        work_.rotation_steps = steps;
        // The sub-steps need only the pieces that can come within a push of where the proxy goes
        // while it turns: for each run of kRotationWindow sub-steps, those within kRotationNear
        // of the run's pushes of where the proxy starts it (a gather about the proxy, not the
        // finger), all of them again with every gathered segment if the proxy leaves that disc.
        // Same pieces in the same order wherever it matters, so the same proxy bit for bit
        // (validation's reference runs the full sub-steps). Why: on a dense contour a sub-step's
        // chord is a quarter of the shortest segment (1 um at 2.5 um segments), so a finger
        // turning 0.4 mrad a tick took 11 sub-steps, each building every segment within the
        // press's reach of the finger: 69,000 segment builds, 7 ms, in a tick.
        bool turned = false;
        if (steps > 1 && def_.use_index && !(kValidation && reference_walk_)) {
            turned = true;
            WarmDisc within{start, 0.0};
            const std::vector<int>* ids = &segment_ids_;
            for (int k = 1; k < steps && turned; ++k) {
                if ((k - 1) % kRotationWindow == 0) {
                    const int last = std::min(k + kRotationWindow - 1, steps - 1);
                    const double near = kRotationNear * (last - k + 1) * sub_push;  // m
                    if (static_cast<int>(segment_ids_.size()) * (last - k + 1) <= kRotationGatherFrom) {
                        // A warm start's few segments, built for the window's sub-steps, cost less
                        // than the query that might find fewer: those, as the full sub-steps below
                        // take them (every point allowed).
                        ids = &segment_ids_;
                        within = WarmDisc{proxy_, std::numeric_limits<double>::infinity()};
                    } else {
                        gather_near(proxy_, phi_ + turn * k / steps, phi_ + turn * last / steps, near + kOnTolerance, rotation_ids_);
                        // (A warm start's few segments can be fewer still: then those.)
                        ids = rotation_ids_.size() < segment_ids_.size() ? &rotation_ids_ : &segment_ids_;
                        within = WarmDisc{proxy_, near - sub_push};
                    }
                }
                build_substep_pieces(phi_ + turn * k / steps, *ids);
                turned = depenetrate(sub_push, &within);
            }
            if (!turned) proxy_ = start;  // went further than guessed: again, with every segment
        }
        for (int k = 1; k < steps && !turned; ++k) {
            build_substep_pieces(phi_ + turn * k / steps, segment_ids_);
            depenetrate(sub_push);
        }
        build_pieces(phi);
        depenetrate(sub_push);
    } else {
        work_.rotation_steps = 0;
        build_pieces(phi);
    }
    turned_ = proxy_;
    // Group and run boxes of the final pieces only: the walk is the one user. A finger resting
    // or sliding slowly on a small scene keeps last tick's pieces, and their boxes.
    if (pieces_changed_) {
        pieces_changed_ = false;
        group_boxes_.clear();
        run_boxes_.clear();
        for (std::size_t i = 0; i < pieces_.size(); ++i) {
            if (i % kPieceGroup == 0) group_boxes_.emplace_back();
            if (i % kPieceRun == 0) run_boxes_.emplace_back();
            group_boxes_.back().grow(piece_boxes_[i]);
            run_boxes_.back().grow(piece_boxes_[i]);
        }
    }
    clock_.lap(stages_.pieces);
    proxy_ = walk(proxy_, finger);
    clock_.lap(stages_.walk);
}

// The squares, a root at the end: max of the roots is the root of the max (sqrt is monotone and
// correctly rounded), the same bits as glm::length of the farthest, without a root a walk step.
void Proxy::note_path(Vec2 p) {
    const Vec2 d = p - path_center_;
    path_extent2_ = std::max(path_extent2_, glm::dot(d, d));
}
void Proxy::note_path_box(const Aabb& box) { path_extent2_ = std::max(path_extent2_, box.max_distance_squared_to(path_center_)); }
double Proxy::path_extent() const { return std::sqrt(path_extent2_); }

// The segments whose c-space pieces can come within `reach` (m) of the finger while the pad turns
// from phi_ to phi: every piece the walk and the re-projection can meet. Pad-interior and vertex
// pieces are the segment offset by R along its free-side normals (AabbTree::query_pad_reach);
// endpoint pieces are the segment seen from a pad end, so they matter for segments within reach
// of the pad ends' positions, which during the turn stay within the chord (<= reach) of the ends.
// Under a pad pressed into a densely sampled contour this keeps the few segments near the
// contact instead of the thousands in the box around the pad.
void Proxy::gather_for_motion(Vec2 finger, double phi, double reach) {
    // The pad's ends sweep from phi_ to phi: the box of both positions covers the arc between
    // them to within its sagitta, which is at most the chord max_push, already inside `reach`.
    // (It was grown by 2 x reach: at 100,000 segments on 0.4 m that gathered thousands more and
    // cost twice the tick; a test compares against use_index = false in contact.)
    gather_near(finger, phi_, phi, reach, segment_ids_);
}

void Proxy::gather_within_reach(Vec2 finger, double phi, double reach) {
    // A pad-end piece is its segment moved by -R u_end: its points within `reach` of the finger
    // come from segment points within `reach` of the pad's end.
    gather_near(finger, phi, phi, reach, segment_ids_);
}

void Proxy::gather_near(Vec2 finger, double phi_from, double phi_to, double reach, std::vector<int>& out) {
    AabbTree::PadReach q;
    if (!start_gather(finger, phi_from, phi_to, reach, q, out)) return;
    env_->tree.continue_pad_reach(q, 0, out);
    finish_gather(out);
}

bool Proxy::start_gather(Vec2 finger, double phi_from, double phi_to, double reach, AabbTree::PadReach& q,
                         std::vector<int>& out) {
    out.clear();
    // A small scene at an unchanged angle: all of it (see kSmallScene). While the finger turns
    // every piece is built anew, and then the index's few are cheaper.
    if (!def_.use_index || gathers_all(phi_from, phi_to)) {
        for (int i = 0; i < static_cast<int>(env_->segments.size()); ++i) out.push_back(i);
        return false;
    }
    // The offset pieces, the inner ones, and the segments within reach of each pad end as it
    // turns, all in one walk of the tree (four walks were a fifth of a small scene's tick), each
    // segment once. A pad end turning by the shortest way (at most a half-turn) from e0 to e1 stays
    // within |e1 - e0| / 2 of their midpoint (the arc's sagitta is at most half its chord), so a
    // disc there covers it. (Boxes around the ends, 2 reach wide, held thousands more on a
    // dense slope when hovering 1 cm above it.)
    const FingerShape& shape = def_.finger;
    const bool ends = pad_has_endpoints(shape);
    const double h = pad_half_angle(shape);  // rad
    Vec2 end_centres[2];
    double half_chord = 0.0;  // m
    if (phi_from == phi_to) {
        const PadFrame& pad = pad_frame(phi_to);  // the ends' directions, computed once per angle
        for (int k = 0; k < 2; ++k) end_centres[k] = finger + shape.radius * pad.end_dir[k];
    } else {
        for (int k = 0; k < 2; ++k) {
            const double side = k == 0 ? -1.0 : 1.0;
            const Vec2 e0 = finger + shape.radius * unit_at(pad_mid_angle(phi_from) + side * h);
            const Vec2 e1 = finger + shape.radius * unit_at(pad_mid_angle(phi_to) + side * h);
            end_centres[k] = 0.5 * (e0 + e1);
            half_chord = 0.5 * glm::length(e1 - e0);
        }
    }
    // Offset and inner pieces press along normals opposite the pad's span (turned by pi); while
    // the pad turns, those of every angle between (the span swept by the shortest turn).
    const double turn = wrap_pi(phi_to - phi_from);  // rad
    const NormalCone outer_normals = h >= kPi ? NormalCone{0.0, kTwoPi}
                                              : NormalCone{wrap_2pi(pad_mid_angle(phi_from) - h + std::min(turn, 0.0) + kPi),
                                                           2.0 * h + std::abs(turn)};
    env_->tree.start_pad_reach(q, finger, shape.radius, reach, ends, end_centres, ends ? 2 : 0, reach + half_chord,
                               outer_normals);
    return true;
}

void Proxy::finish_gather(std::vector<int>& out) {
    // Sorted, so the pieces' order (and thus tie-breaks) does not depend on the tree. (Along a
    // contour the tree's order usually is sorted already: checking is linear, sorting is not.)
    if (!std::is_sorted(out.begin(), out.end())) std::sort(out.begin(), out.end());
}

// The pad frame at phi, kept from the last call while phi and the finger stay the same: its sines,
// cosines and arctangents were a tenth of a small scene's tick, and a device that does not turn
// the finger keeps phi fixed.
const PadFrame& Proxy::pad_frame(double phi) {
    if (!(pad_frame_valid_ && pad_frame_.phi == phi && pad_frame_.finger == def_.finger)) {
        pad_frame_ = make_pad_frame(def_.finger, phi);
        pad_frame_valid_ = true;
    }
    return pad_frame_;
}

// pieces_ (and their boxes, piece_boxes_) for segment_ids_ at phi. A segment's pieces depend only
// on the segment and the pad frame, so at the angle of the last build the pieces of segments built
// then are copied, not made again: a finger sliding over a dense contour keeps most of last tick's
// segments, a small scene all of them (building was a fifth of the tick). Same pieces, same order.
void Proxy::build_pieces(double phi) {
    active_count_ = 0;
    const PadFrame& pad = pad_frame(phi);
    if (segment_ids_.empty()) {
        pieces_changed_ = true;
        local_valid_ = false;
        // Nothing near (a free finger's motion): keep the last build aside for the next one to
        // copy from (anticipation's, a tick later) instead of forgetting it.
        if (!cache_aside_) {
            std::swap(pieces_, aside_pieces_);
            std::swap(piece_boxes_, aside_boxes_);
            cache_aside_ = true;
        }
        pieces_.clear();
        piece_boxes_.clear();
        return;
    }
    const bool reuse = built_valid_ && phi == built_phi_;
    // The same pieces: keep them, and the last scan's list of those near the walk (local_), which
    // still lists every piece whose box overlaps local_box_ (a tick's first scan then asks it
    // instead of every piece: over a dense contour four ticks in five keep their pieces).
    if (reuse && !cache_aside_ && segment_ids_ == built_ids_) return;
    pieces_changed_ = true;
    local_valid_ = false;
    next_pieces_.clear();
    next_boxes_.clear();
    next_first_.clear();
    std::size_t j = 0;  // position in built_ids_ (both lists are sorted)
    for (const int id : segment_ids_) {
        next_first_.push_back(static_cast<int>(next_pieces_.size()));
        append_segment_pieces(id, pad, reuse, j, next_pieces_, next_boxes_);
    }
    next_first_.push_back(static_cast<int>(next_pieces_.size()));
    std::swap(pieces_, next_pieces_);
    std::swap(piece_boxes_, next_boxes_);
    std::swap(built_first_, next_first_);
    cache_aside_ = false;
    built_ids_.assign(segment_ids_.begin(), segment_ids_.end());
    built_phi_ = phi;
    built_valid_ = true;
}

// Segment id's pieces at pad (and their boxes), appended: copied from the last build (pieces_, or
// aside_pieces_ while set aside) when that was at this angle (reuse), else made. j: a cursor in
// built_ids_, for ids asked in ascending order.
void Proxy::append_segment_pieces(int id, const PadFrame& pad, bool reuse, std::size_t& j, std::vector<CPiece>& pieces,
                                  std::vector<Aabb>& boxes) {
    const std::vector<CPiece>& old_pieces = cache_aside_ ? aside_pieces_ : pieces_;
    const std::vector<Aabb>& old_boxes = cache_aside_ ? aside_boxes_ : piece_boxes_;
    // The segment's pieces in the last build (at built_phi_), if it was built then. A segment
    // that had none at that angle has none now: copied as nothing, not built again (at the
    // bottom of a valley tighter than the pad, most segments gathered have no piece, and
    // building them again made 2,000 of a slow tick's 2,300 builds).
    int old_from = 0, old_to = 0;
    bool was_built = false;
    if (built_valid_) {
        while (j < built_ids_.size() && built_ids_[j] < id) ++j;
        if (j < built_ids_.size() && built_ids_[j] == id) {
            old_from = built_first_[j], old_to = built_first_[j + 1];
            was_built = true;
        }
    }
    if (reuse && was_built) {
        for (int k = old_from; k < old_to; ++k) {
            pieces.push_back(old_pieces[static_cast<std::size_t>(k)]);
            boxes.push_back(old_boxes[static_cast<std::size_t>(k)]);
        }
        return;
    }
    const std::size_t from = pieces.size();
    append_cspace_pieces(*env_, id, pad, pieces);
    ++work_.built_segments;
    for (std::size_t k = from; k < pieces.size(); ++k) {
        // A circle's box is arc_bounds' two sincos: a piece the turn left as it was (an arc's
        // offset or inner circle whose span the pad's still holds whole, made of the segment
        // alone) keeps the box it had, the same function of the same bits.
        const CPiece& piece = pieces[k];
        const int old = old_from + static_cast<int>(k - from);
        if (piece.kind == CPiece::Kind::circle && old < old_to &&
            same_circle(piece, old_pieces[static_cast<std::size_t>(old)])) {
            boxes.push_back(old_boxes[static_cast<std::size_t>(old)]);
            continue;
        }
        boxes.push_back(piece_box(piece).grown(kBoxSlack));
    }
}

// pieces_ for segment_ids_ at a re-projection sub-step's angle: no boxes (only the walk uses them)
// and nothing kept to copy (no later build asks for this angle). A large turn over a dense contour
// takes hundreds of sub-steps.
void Proxy::build_substep_pieces(double phi, const std::vector<int>& ids) {
    active_count_ = 0;
    pieces_changed_ = true;
    local_valid_ = false;
    const PadFrame& pad = pad_frame(phi);
    pieces_.clear();
    piece_boxes_.clear();
    for (const int id : ids) append_cspace_pieces(*env_, id, pad, pieces_);
    work_.built_segments += static_cast<int>(ids.size());
    built_valid_ = false;
    cache_aside_ = false;
}

// After phi changed, pieces made by the pad's ends moved by at most `max_push` (m). If the proxy
// ended up inside the obstacle, push it back out along the normal of the piece it is deepest
// behind. If that push lands behind a second piece, the nearest free point is their corner: both
// pad ends wedged in a valley, say, where the pad is lifted out as it turns. Alternating pushes
// between two nearly opposite pieces converge slowly (by cos^2 of their angle per round), and the
// few allowed left the proxy a micrometre behind one of them, which the walk then passed through
// as if it were not there (fuzz-contact: the pad dropped 12 mm into a crevice).
bool Proxy::depenetrate(double max_push, const WarmDisc* within) {
    // Every point the pieces are asked about must lie inside `within` (when given): false as soon
    // as one does not, the proxy left where it was.
    auto outside = [&](Vec2 x) { return within != nullptr && glm::length(x - within->center) > within->radius; };
    // The piece the point x is deepest behind (depth <= max_push), or -1.
    auto deepest_behind = [&](Vec2 x, int skip, double& depth) {
        int deepest = -1;
        double deepest_d = -kOnTolerance;
        for (int i = 0; i < static_cast<int>(pieces_.size()); ++i) {
            if (i == skip) continue;
            const CPiece& piece = pieces_[i];
            const double d = piece_signed_distance(piece, x);
            if (d >= deepest_d || d < -max_push) continue;
            if (!inside_or_past_concave_end(piece, piece_param(piece, x), max_push)) continue;
            deepest = i;
            deepest_d = d;
        }
        depth = -deepest_d;
        return deepest;
    };
    for (int it = 0; it < kMaxDepenetrationIterations; ++it) {
        if (outside(proxy_)) return false;
        double depth = 0.0;
        const int a = deepest_behind(proxy_, -1, depth);
        if (a < 0) return true;
        const CPiece& pa = pieces_[a];
        const Vec2 pushed = proxy_ + depth * piece_normal_at(pa, proxy_);
        note_path(pushed);
        if (outside(pushed)) return false;
        double depth_b = 0.0;
        const int b = deepest_behind(pushed, a, depth_b);
        if (b < 0) {
            proxy_ = pushed;
            return true;
        }
        // Onto both boundaries: Newton on (d_a(x), d_b(x)) = 0, whose Jacobian rows are the normals.
        const CPiece& pb = pieces_[b];
        Vec2 x = proxy_;
        bool converged = false;
        for (int k = 0; k < 16; ++k) {
            const double fa = piece_signed_distance(pa, x), fb = piece_signed_distance(pb, x);
            if (std::abs(fa) <= 1e-14 && std::abs(fb) <= 1e-14) { converged = true; break; }
            const Vec2 na = piece_normal_at(pa, x), nb = piece_normal_at(pb, x);
            const double det = cross(na, nb);
            if (!(std::abs(det) > 1e-12)) break;  // parallel boundaries: no corner to stand in
            // Solve [na; nb] dx = (-fa, -fb) by Cramer's rule.
            x += Vec2{(-fa * nb.y + fb * na.y) / det, (-fb * na.x + fa * nb.x) / det};
        }
        // A corner far beyond what the pieces moved belongs to another branch of the circles.
        if (converged && glm::length(x - proxy_) <= kMaxCornerPushFactor * max_push) {
            note_path(x);
            proxy_ = x;
        } else {
            proxy_ = pushed;
        }
    }
    return true;
}

// True when `param` lies on the piece, or beyond one of its ends by at most `reach` (m) where
// that end sits at a concave junction of the contour. Near a concave corner the solid is the
// union of both sides' half-planes, so a pad end rotated into the corner is behind both pieces'
// extensions and within neither piece: it must still be pushed out.
bool Proxy::inside_or_past_concave_end(const CPiece& piece, double param, double reach) const {
    const bool line = piece.kind == CPiece::Kind::line;
    const double on_slack = line ? kOnTolerance : kOnTolerance / piece.radius;
    if (piece_param_inside(piece, param, on_slack)) return true;
    // Vertices are convex by definition; inner pieces end where the pad's concave side stops
    // facing the contour, not at a junction of it.
    if (piece.source == CPiece::Source::vertex || piece.source == CPiece::Source::vertex_inner ||
        piece.source == CPiece::Source::arc_inner) return false;
    const EnvSegment& seg = env_->segments[static_cast<std::size_t>(piece.segment)];
    auto concave_at_start = [&] { return seg.prev >= 0 && env_->segments[seg.prev].end_cone.width <= 0.0; };
    auto concave_at_end = [&] { return seg.next >= 0 && seg.end_cone.width <= 0.0; };
    if (line) {
        if (param < 0.0) return param >= -reach && concave_at_start();
        return param <= piece.len + reach && concave_at_end();
    }
    // Circle pieces of an arc: the span's ends are the segment's ends only where the piece was
    // not trimmed there; the low angle is the travel start for a bowl (counter-clockwise travel).
    // Past an end by at most `reach` of arc, and never by more than a quarter turn: a bowl whose
    // radius is within a hair of the pad's has an offset circle of a few micrometres, and an
    // angular reach of reach / radius (several radians) made it claim nearly every point round it
    // as "behind its end", so the corner push chased it against a neighbour's piece and left the
    // pad's end inside the curve (fuzz-contact, case seed 11419799571873864837).
    const double angular_reach = std::min(reach / piece.radius, 0.5 * kPi);
    const double tol = 1e-12;
    const double span_end = piece.span.start + piece.span.width;
    const double seg_end = seg.angles.start + seg.angles.width;
    if (param < 0.0) {
        if (param < -angular_reach || std::abs(wrap_pi(piece.span.start - seg.angles.start)) > tol) return false;
        return seg.free_outside ? concave_at_end() : concave_at_start();
    }
    if (param > piece.span.width + angular_reach || std::abs(wrap_pi(span_end - seg_end)) > tol) return false;
    return seg.free_outside ? concave_at_start() : concave_at_end();
}

// At a junction the obstacle's boundary passes from one piece to the next. A motion from `at` (on
// piece i) along unit direction t that leaves piece i off its end is judged by the piece it moves
// onto, if any piece through `at` keeps t within its extent (a convex junction, or a tangential
// one). If none does, t points into the wedge beyond both ends: at a concave junction that wedge
// is solid, so piece i's own normal still decides (returns false).
bool Proxy::handed_over(int i, const Vec2& at, const Vec2& t, int ended) const {
    if (!leaves_range(pieces_[i], at, t)) return false;
    auto continues = [&](int j) {  // piece j passes through `at` and keeps t within its extent
        if (j == i || j == ended || !piece_boxes_[static_cast<std::size_t>(j)].contains(at)) return false;
        const CPiece& other = pieces_[j];
        if (std::abs(piece_signed_distance(other, at)) > kOnTolerance) return false;
        const double slack = other.kind == CPiece::Kind::line ? kOnTolerance : kOnTolerance / other.radius;
        if (!piece_param_inside(other, piece_param(other, at), slack)) return false;
        return !leaves_range(other, at, t);
    };
    if (local_scans_allowed() && local_near(at, kLocalAcceptRadius)) {  // every box holding `at` is among the last scan's
        for (const int j : local_)
            if (continues(j)) return true;
        return false;
    }
    bool found = false;
    for_pieces([&](const Aabb& box) { return !box.contains(at); }, [&](int j) { return found = continues(j); });
    return found;
}

template <typename Far, typename Visit>
void Proxy::for_pieces(Far&& far, Visit&& visit) const {
    const int count = static_cast<int>(pieces_.size());
    for (int i = 0; i < count;) {
        if (i % kPieceRun == 0 && far(run_boxes_[static_cast<std::size_t>(i / kPieceRun)])) {
            i += kPieceRun;  // the whole run is far
            continue;
        }
        if (i % kPieceGroup == 0 && far(group_boxes_[static_cast<std::size_t>(i / kPieceGroup)])) {
            i += kPieceGroup;  // the whole group is far
            continue;
        }
        if (!far(piece_boxes_[static_cast<std::size_t>(i)]) && visit(i)) return;
        ++i;
    }
}

bool Proxy::local_holds(const Aabb& box) const {
    return local_valid_ && local_scans_allowed() && local_box_.contains(box);
}

double Proxy::chain_reach() const {
    const double shortest = env_->min_feature;  // m (infinite for an empty scene)
    return shortest < kMaxChainReach ? std::max(shortest, 0.0) : kMaxChainReach;
}

// Calls ask(i) in order for every piece whose box overlaps `scan`: from local_ when it holds them
// all (or from_local, when the caller has judged so), else from every piece, keeping as local_
// those within chain_reach() of `scan` (more pieces kept, the same ones asked: the box test only
// rejects pieces that cannot be entered). Either way the same pieces in the same order.
template <typename Ask, typename Ahead>
void Proxy::scan_pieces(const Aabb& scan, bool from_local, Ask&& ask, Ahead&& ahead_of_motion) {
    if (from_local || local_holds(scan)) {
        ++work_.chain_scans;
        for (const int i : local_)
            if (piece_boxes_[static_cast<std::size_t>(i)].overlaps(scan)) ask(i);
        return;
    }
    ++work_.full_scans;
    local_valid_ = false;  // handed_over must not read the list while it is being filled
    local_.clear();
    Aabb kept = scan.grown(chain_reach());
    const double further = kChainAhead * chain_reach();  // m, ahead along `ahead`
    const Vec2 ahead = ahead_of_motion();
    (ahead.x > 0.0 ? kept.hi.x : kept.lo.x) += further * ahead.x;
    (ahead.y > 0.0 ? kept.hi.y : kept.lo.y) += further * ahead.y;
    for_pieces([&](const Aabb& box) { return !box.overlaps(kept); },
               [&](int i) {
                   local_.push_back(i);
                   if (piece_boxes_[static_cast<std::size_t>(i)].overlaps(scan)) ask(i);
                   return false;
               });
    local_box_ = kept;
    local_valid_ = true;
}

bool Proxy::local_near(Vec2 at, double within) const {
    // Boxes that come within kNearMargin of a point `within` of `at` overlap local_box_ if that
    // point's margin box lies inside it.
    const double m = within + kNearMargin;
    return local_valid_ && at.x - m >= local_box_.lo.x && at.x + m <= local_box_.hi.x && at.y - m >= local_box_.lo.y &&
           at.y + m <= local_box_.hi.y;
}

// ---- Proxy::walk --------------------------------------------------------------------------------
Vec2 Proxy::walk(Vec2 p, Vec2 goal) {
    active_count_ = 0;
    // local_ stays valid while pieces_ does (whatever rebuilds pieces_ clears local_valid_), but a
    // long list is dropped: every chain scan asks each of its boxes, and one kept from a long
    // move's scan made every scan of the next ticks slower than a fresh scan of every piece's
    // runs (dense curves' p99.9, least of 3 passes, 52 -> 63 us).
    if (local_.size() > kLocalKeptAcrossTicks) local_valid_ = false;
    work_.near_start = false;
    work_.chain_scans = work_.full_scans = 0;
    int excluded = -1;     // the piece just slid off the end of (not re-entered at its end)
    int idle_steps = 0;    // consecutive steps that did not move the proxy
    proxy_ = p;
    work_.walk_steps = 0;
    for (int it = 0; it < kMaxWalkIterations; ++it) {
        work_.walk_steps = it + 1;
        if (active_count_ == 0) {
            // The piece just slid off cannot be where the boundary continues: if the move toward
            // the finger heads back over it (a circle's chord from its end into a concave
            // junction), the neighbour through the junction is entered (fuzz-contact found the
            // proxy leaving a terrain's valley corner into the solid).
            // Off a piece's end the move usually enters the next piece at once: asked first of
            // the pieces the last scan kept near here, and of all only if none is entered there.
            Hit hit;
            if (excluded >= 0 && local_scans_allowed() && local_near(proxy_, kLocalAcceptRadius)) {
                hit = first_entry_line(proxy_, goal, excluded, -1, excluded, Scan::among_local);
                if (!(hit.found && glm::length(hit.point - proxy_) <= kLocalAcceptRadius)) hit = Hit{};
            } else if (it == 0 && resting_ && local_scans_allowed()) {
                // The walk's first move, from a proxy resting on a piece: it enters that piece (or
                // a neighbour through the same point) at once, so the pieces near the proxy
                // answer it, by the same rule. Why: the move toward a finger pressed 1 mm in
                // spans a box that held ~70 pieces of a dense contour, each asked, every tick.
                hit = first_entry_line(proxy_, goal, -1, -1, -1, Scan::near_start);
                work_.near_start = hit.found && glm::length(hit.point - proxy_) <= kLocalAcceptRadius;
                if (!work_.near_start) hit = Hit{};
            }
            if (!hit.found) hit = first_entry_line(proxy_, goal, excluded, -1, excluded);
            const int ended = excluded;
            excluded = -1;
            // Off a piece's end at a concave junction, with the finger in the wedge beyond both
            // pieces' ends: that wedge is solid, so the piece's own normal still decides
            // (handed_over). The proxy rests at the junction; before, the straight move crossed
            // the piece's extension into the solid (fuzz-contact: a terrain valley). That holds
            // whatever the move would meet further on: the wedge is solid from the junction
            // itself, so only a piece entered right there (within kOnTolerance, m) comes first.
            // (A far piece used to win: a pad end in a terrain's valley, the hand 12 cm away
            // under the terrain, went straight through the solid to a thin wall's inner vertex
            // piece 7.5 mm off; fuzz-contact, case seed 14920330087293500056.)
            // (A hit at the start, s = 0, is entered within kOnTolerance whatever the move's length:
            // over a dense contour nearly every entry, so the length is not taken for it.)
            const Vec2 v = goal - proxy_;
            const double v_len = ended >= 0 && !(hit.found && hit.s == 0.0) ? glm::length(v) : 0.0;  // m
            if (ended >= 0 && v_len > 0.0 && !(hit.found && hit.s * v_len <= kOnTolerance) &&
                pressing(pieces_[ended], proxy_, goal) && !handed_over(ended, proxy_, v / v_len)) {
                active_[0] = ended;
                active_count_ = 1;
                return proxy_;
            }
            if (!hit.found) {  // free motion all the way
                note_path(goal);
                return goal;
            }
            note_path(hit.point);
            proxy_ = hit.point;
            active_[0] = hit.piece;
            active_count_ = 1;
            continue;
        }
        if (active_count_ == 2) {
            if (!try_release_corner(goal)) return proxy_;  // resting in a corner: two contacts
            continue;
        }
        const int current = active_[0];
        const CPiece& piece = pieces_[current];
        if (!pressing(piece, proxy_, goal)) {  // the motion toward the finger leaves this piece
            active_count_ = 0;
            continue;
        }
        const PieceFoot foot = piece_foot(piece, goal);
        const bool line = piece.kind == CPiece::Kind::line;
        // rad along a circle from its span's start (a line's slide needs none)
        const double s0 = line ? 0.0 : std::clamp(piece_param(piece, proxy_), 0.0, piece.span.width);
        // A slide of at most kOnTolerance (m) is no motion: it enters nothing. The entry tests
        // accept hits within kOnTolerance of the start, a slack that then covers the whole slide
        // and more: at a piece's end with the foot a rounding error away (a circle's |ds| of
        // 6e-15 rad) the other piece through the junction read as entered at once, and the walk
        // went corner, release, slide, corner... on the spot until its step cap, every tick
        // (fuzz-contact, case seed 14920330087293500056).
        const double chord = glm::length(foot.point - proxy_);  // m, the step to the foot
        const double slide = line ? chord : piece.radius * std::abs(foot.param - s0);
        Hit hit;
        if (slide <= kOnTolerance) {
            // no motion: nothing entered
        } else if (line) {
            hit = first_entry_line(proxy_, foot.point, current, -1);
        } else {
            hit = first_entry_arc(piece, s0, foot.param, current);
            // The slide follows the circle, which may bulge beyond both its ends: its box, as
            // first_entry_arc made it (the same arc: making it again was 2 % of a dense tick).
            // Entered on the way, only the arc up to the entry: a piece can change the answer
            // only by being entered before it. (The whole arc toward a foot far round a pad-end
            // circle, noted for a slide blocked at once in a corner, failed the warm start of every
            // tick of a finger wedged between a gear's teeth: 6,300 segments gathered, 0.6 ms.)
            if (hit.found) {
                const double s_hit = s0 + hit.s * (foot.param - s0);  // rad
                note_path_box(arc_bounds(piece.center, piece.radius, piece.span.start + std::min(s0, s_hit), std::abs(s_hit - s0)));
            } else {
                note_path_box(arc_slide_box_);
            }
        }
        if (hit.found) {  // slid into another piece: a corner
            note_path(hit.point);
            proxy_ = hit.point;
            active_[1] = hit.piece;
            active_count_ = 2;
            continue;
        }
        const double step = chord;  // the scans above do not move proxy_
        note_path(foot.point);
        proxy_ = foot.point;
        if (!foot.clamped) return proxy_;  // resting on this piece: one contact
        // Reached the piece's end: the boundary continues on a neighbouring piece, which a
        // straight move toward the finger now enters at once.
        idle_steps = step <= kOnTolerance ? idle_steps + 1 : 0;
        if (idle_steps >= 3) return proxy_;  // the nearest point is this junction itself
        active_count_ = 0;
        excluded = current;
    }
    return proxy_;
}

// In a corner between pieces P and Q: keep sliding along one of them if that does not enter the
// other; return false when both block (the proxy rests in the corner).
bool Proxy::try_release_corner(Vec2 goal) {
    const int ids[2] = {active_[0], active_[1]};
    const bool p0 = pressing(pieces_[ids[0]], proxy_, goal);
    const bool p1 = pressing(pieces_[ids[1]], proxy_, goal);
    if (!p0 && !p1) { active_count_ = 0; return true; }
    // Sliding along piece k toward the goal's foot on it: +1 when that keeps out of the other
    // piece (or passes its end onto a piece that continues), -1 when it enters the other at once,
    // 0 when there is no slide (the foot is here).
    auto slide = [&](int k) {
        const CPiece& along = pieces_[ids[k]];
        const CPiece& other = pieces_[ids[1 - k]];
        const PieceFoot foot = piece_foot(along, goal);
        const double s0 = piece_param(along, proxy_);
        const double ds = foot.param - s0;
        if (std::abs(ds) <= kTangentTolerance) return 0;
        const Vec2 t = along.kind == CPiece::Kind::line ? (ds > 0 ? along.dir : -along.dir)
                                                        : arc_tangent(along, s0, ds > 0 ? 1.0 : -1.0);
        // Either piece's rounding tilts the comparison: take the looser of the two tolerances.
        const double tol = std::max(graze_tolerance(other), graze_tolerance(along));
        return glm::dot(t, piece_normal_at(other, proxy_)) > -tol || handed_over(ids[1 - k], proxy_, t) ? 1 : -1;
    };
    if (!p0 || !p1) {
        // Only piece k is pressed: slide along it, unless that slide enters the other piece at
        // once. Then the proxy rests in the corner: with the straight move (direction g) behind
        // k's boundary only (g.n_k < 0 <= g.n_o) and k's slide direction t behind the other's
        // (t.n_o < 0), the normals are more than 90 degrees apart, and g points away from both
        // edges of the free wedge {d : d.n_k >= 0, d.n_o >= 0}: its nearest point in the wedge is
        // the apex. Releasing anyway re-entered the other piece at once, corner, release... on
        // the spot until the walk's step cap, every tick (fuzz-contact, case seed
        // 14920330087293500056: a pad end against a thin wall's foot, the hand 10 cm away).
        const int k = p0 ? 0 : 1;
        if (slide(k) < 0) return false;
        active_[0] = ids[k];
        active_count_ = 1;
        return true;
    }
    for (int k = 0; k < 2; ++k) {
        if (slide(k) > 0) {
            active_[0] = ids[k];
            active_count_ = 1;
            return true;
        }
    }
    return false;
}

// ---- first_entry_line / first_entry_arc --------------------------------------------------------
Proxy::Hit Proxy::first_entry_line(const Vec2& p, const Vec2& q, int exclude_a, int exclude_b, int ended, Scan scan_kind) {
    Hit best;
    const Vec2 v = q - p;
    const double len = glm::length(v);
    if (len <= 0.0) return best;
    // kOnTolerance along the motion (the slack of an entry at its start): asked only of a piece
    // entered there, so taken then (a division each of the dense walk's ~28 scans a tick).
    double t_slack_once = -1.0;
    auto t_slack = [&] { return t_slack_once >= 0.0 ? t_slack_once : (t_slack_once = kOnTolerance / len); };
    Aabb motion;
    motion.grow(p);
    motion.grow(q);
    motion = motion.grown(kBoxSlack);
    auto consider = [&](int i) {
        if (i == exclude_a || i == exclude_b) return;
        const CPiece& piece = pieces_[i];
        if (piece.kind == CPiece::Kind::line) {
            const double den = glm::dot(v, piece.n);
            if (den >= -kTangentTolerance * len) return;  // parallel or leaving
            const double d0 = piece_signed_distance(piece, p);
            if (d0 < -kOnTolerance) return;                // started behind it: not entering
            if (d0 + den >= 0.0) return;                   // does not reach it
            const double t = std::clamp(d0 / -den, 0.0, 1.0);
            if (t >= best.s) return;
            const Vec2 x = p + t * v;
            if (!piece_param_inside(piece, piece_param(piece, x), kOnTolerance)) return;
            if (t <= t_slack() && handed_over(i, x, v / len, ended)) return;
            best = {true, t, x, i};
        } else {
            if (piece.free_outside && std::abs(piece_signed_distance(piece, p)) <= kOnTolerance) {
                // Starting on a convex circle, the path enters only if it heads inward here; it
                // cannot come back to the circle later. (The roots are useless here: a start
                // 1e-13 m inside turns a tangent path into a 1e-7 m chord with a steep "entry".)
                if (0.0 >= best.s) return;
                const Vec2 radial = glm::normalize(p - piece.center);
                if (glm::dot(v, radial) / len >= -graze_tolerance(piece)) return;
                if (handed_over(i, p, v / len, ended)) return;
                if (!piece_param_inside(piece, piece_param(piece, p), kOnTolerance / piece.radius)) return;
                best = {true, 0.0, p, i};
                return;
            }
            double roots[2];
            const int n = line_circle(p, v, piece.center, piece.radius, roots);
            for (int k = 0; k < n; ++k) {
                const double t = roots[k];
                if (t > 1.0 || t >= best.s || t < -t_slack()) continue;
                const Vec2 x = p + t * v;
                // Within the circle's span only if inside its box (grown by kBoxSlack, ten times
                // the span's slack): a crossing of the rest of the circle is refused before the
                // arctangent, the same refusal.
                if (!piece_boxes_[static_cast<std::size_t>(i)].contains(x)) continue;
                const Vec2 radial = (x - piece.center) / piece.radius;
                const double along = glm::dot(v, radial) / len;
                const bool entering = piece.free_outside ? along < -graze_tolerance(piece)
                                                         : along > kTangentTolerance;
                if (!entering) continue;
                if (!piece_param_inside(piece, piece_param(piece, x), kOnTolerance / piece.radius)) {
                    continue;
                }
                if (t <= t_slack() && handed_over(i, x, v / len, ended)) continue;
                best = {true, std::max(t, 0.0), t < 0.0 ? p : x, i};
            }
        }
    };
    // The pieces asked: those whose boxes overlap `scan`, in order. Near the start, only the
    // pieces that can be entered within kLocalAcceptRadius of p (the caller judges the answer).
    Aabb scan;
    if (scan_kind == Scan::full) {
        scan = motion.grown(kNearMargin + kLocalAcceptRadius);
    } else {
        scan.grow(p);
        scan = scan.grown(kBoxSlack + kNearMargin + kLocalAcceptRadius);
    }
    // A full scan's list is kept further along the motion: the walk goes on that way.
    scan_pieces(scan, scan_kind == Scan::among_local, consider, [&] { return scan_kind == Scan::full ? v / len : Vec2{0.0}; });
    return best;
}

Proxy::Hit Proxy::first_entry_arc(const CPiece& on, double s0, double s1, int exclude) {
    Hit best;
    const double ds = s1 - s0;
    arc_slide_box_ = arc_bounds(on.center, on.radius, on.span.start + std::min(s0, s1), std::abs(ds));
    if (std::abs(ds) * on.radius <= 0.0) return best;
    const double direction = ds > 0.0 ? 1.0 : -1.0;
    const double s_slack = kOnTolerance / (on.radius * std::abs(ds));
    // A point entered on the way lies on the slide's arc (up to kOnTolerance before its start),
    // so inside its box grown by a few times that: a crossing outside it (the far one of two
    // circles) is refused with four comparisons instead of two arctangents, the same refusal.
    const Aabb on_slide = arc_slide_box_.grown(4.0 * kOnTolerance);
    auto consider = [&](int i, Vec2 x) {
        if (!on_slide.contains(x)) return;
        // ... and on the piece entered, within its span: inside its box (grown by kBoxSlack, ten
        // times the span's slack). The same refusal again, before the piece's arctangent.
        if (!piece_boxes_[static_cast<std::size_t>(i)].contains(x)) return;
        const CPiece& piece = pieces_[i];
        const double slack = piece.kind == CPiece::Kind::line ? kOnTolerance
                                                              : kOnTolerance / piece.radius;
        if (!piece_param_inside(piece, piece_param(piece, x), slack)) return;
        const double s_on = piece_param(on, x);
        const double s = (s_on - s0) / ds;
        if (s < -s_slack || s > 1.0 || s >= best.s) return;
        const Vec2 t = arc_tangent(on, s_on, direction);
        const double tol = std::max(graze_tolerance(piece), graze_tolerance(on));
        if (glm::dot(t, piece_normal_at(piece, x)) >= -tol) return;  // not entering
        if (handed_over(i, x, t)) return;
        best = {true, std::max(s, 0.0), s < 0.0 ? proxy_ : x, i};
    };
    const Aabb motion = arc_slide_box_.grown(kBoxSlack + kNearMargin + kLocalAcceptRadius);
    auto ask = [&](int i) {
        if (i == exclude) return;
        const CPiece& piece = pieces_[i];
        if (piece.kind == CPiece::Kind::line) {
            double roots[2];
            const int n = line_circle(piece.a, piece.dir, on.center, on.radius, roots);
            for (int k = 0; k < n; ++k) consider(i, piece.a + roots[k] * piece.dir);
        } else {
            Vec2 pts[2];
            const int n = circle_circle(on.center, on.radius, piece.center, piece.radius, pts);
            for (int k = 0; k < n; ++k) consider(i, pts[k]);
        }
    };
    scan_pieces(motion, /*from_local=*/false, ask, [&] { return arc_tangent(on, s0, direction); });
    return best;
}

// ---- collect_contacts ---------------------------------------------------------------------------
// Every piece through the final proxy that the finger presses into is a contact (a corner gives
// two); l_d is their centroid (seed 000). If rounding hides them all, the piece the walk ended
// on stands in.
void Proxy::collect_contacts(Vec2 goal) {
    auto add = [&](const CPiece& piece) {
        if (out_.contact_count >= static_cast<int>(out_.contacts.size())) return;
        ProxyContact c;
        c.point = piece_contact_point(piece, def_.finger, proxy_);
        c.l = piece_contact_location(piece, def_.finger, phi_, proxy_);
        c.segment = piece.segment;
        c.source = piece.source;
        // The same touch can be represented by two pieces meeting at a junction: count it once.
        for (int i = 0; i < out_.contact_count; ++i) {
            if (glm::length(out_.contacts[i].point - c.point) <= kOnTolerance &&
                std::abs(out_.contacts[i].l - c.l) <= kOnTolerance) {
                return;
            }
        }
        contact_pieces_[out_.contact_count] = static_cast<int>(&piece - pieces_.data());
        out_.contacts[out_.contact_count++] = c;
    };
    // A piece the proxy is on holds it within 2 kOnTolerance of its points, so inside its box
    // (grown by kBoxSlack): the box rejects the others with four comparisons. Why first: where
    // the pad lies in a valley of its own shape, hundreds of offset pieces (circles of nearly zero
    // radius about nearly one point) pass within kOnTolerance of the proxy away from their spans,
    // and each asked for its angle (an atan2) to be refused: half of such a tick's instructions.
    // (After a re-projection sub-step's build there are no boxes: every piece is asked.)
    const bool boxed = piece_boxes_.size() == pieces_.size();
    auto consider = [&](std::size_t i) {
        const CPiece& piece = pieces_[i];
        if (std::abs(piece_signed_distance(piece, proxy_)) > kOnTolerance) return;
        if (!pressing(piece, proxy_, goal)) return;
        const double slack = piece.kind == CPiece::Kind::line ? kOnTolerance
                                                              : kOnTolerance / piece.radius;
        if (!piece_param_inside(piece, piece_param(piece, proxy_), slack)) return;
        add(piece);
    };
    if (boxed && !pieces_changed_) {
        // The group and run boxes the walk used hold these boxes: whole runs that cannot hold the
        // proxy are skipped (the same pieces asked, in order; a tenth of a dense tick was this loop).
        for_pieces([&](const Aabb& box) { return !box.contains(proxy_); },
                   [&](int i) { consider(static_cast<std::size_t>(i)); return false; });
    } else {
        for (std::size_t i = 0; i < pieces_.size(); ++i)
            if (!boxed || piece_boxes_[i].contains(proxy_)) consider(i);
    }
    if (out_.contact_count == 0) {
        for (int i = 0; i < active_count_; ++i) add(pieces_[active_[i]]);
    }
}

// ---- contour_leaves_pad_between ---------------------------------------------------------------------
// Two pieces are separate contact pairs only if the contour between their segments leaves the
// finger's circle (radius R about x_f): the pad then overlaps the solid in two places, as on the
// two sides of a valley. Over a convex bump the contour between the near and a far foot stays
// within R, one overlap. Walks the chain between the segments (either way round, at most
// kMaxPairWalk segments) and checks the farthest point of every segment strictly between.
namespace {
constexpr int kMaxPairWalk = 512;
double farthest_distance(const EnvSegment& s, Vec2 from) {
    double d = std::max(glm::length(s.start - from), glm::length(s.end - from));
    if (s.kind == EnvSegment::Kind::arc) {
        const Vec2 away = s.center - from;
        const double len = glm::length(away);
        const double angle = len > 0.0 ? std::atan2(away.y, away.x) : s.angles.start;
        if (span_contains(s.angles, angle)) d = std::max(d, len + s.radius);
    }
    return d;
}
}  // namespace

bool Proxy::contour_leaves_pad_between(int a, int b, Vec2 finger) const {
    const double R = def_.finger.radius;
    for (const bool forward : {true, false}) {
        double farthest = 0.0;
        int s = a;
        for (int step = 0; step < kMaxPairWalk; ++step) {
            const EnvSegment& seg = env_->segments[static_cast<std::size_t>(s)];
            s = forward ? seg.next : seg.prev;
            if (s < 0 || s == a) break;
            if (s == b) return farthest > R;
            farthest = std::max(farthest, farthest_distance(env_->segments[static_cast<std::size_t>(s)], finger));
        }
    }
    return true;  // other contour, or far along this one
}

// ---- apply_force_law ------------------------------------------------------------------------------
// The force on the finger from the proxy's anchor (force_law.hpp): the frictionless proxy, or the
// stiction point held inside the friction cone and slid onto its edge when the force leaves it.
// The contact frame is the direction from the finger to the frictionless proxy (the surface
// normal for one contact, inside the normal cone in a corner).
void Proxy::apply_force_law(Vec2 finger, double dt) {
    const ForceLaw& law = def_.law;
    const Vec2 proxy = out_.proxy;
    const double depth = out_.depth;
    const Vec2 n = depth > 0.0 ? (proxy - finger) / depth : Vec2{0.0, 1.0};
    const Vec2 t = -perp_left(n);
    Vec2 anchor = proxy;
    if (law.mu_static > 0.0) {
        if (!has_stiction_) {
            stiction_ = proxy;
            has_stiction_ = true;
        }
        // Offset of the stiction point along the surface from the frictionless proxy: the force
        // toward it has F_t / F_n = sigma / depth for both laws (the ellipsoid keeps direction -p).
        const double sigma = glm::dot(stiction_ - proxy, t);
        if (std::abs(sigma) > law.mu_static * depth) {
            stiction_ = proxy + std::copysign(law.mu_dynamic * depth, sigma) * t;
            out_.sliding = true;
        }
        anchor = stiction_;
    }
    Vec2 force = law.model == ForceModel::ellipsoid ? ellipsoid_force(finger - anchor, n, law.k_tangential, law.k_normal, law.field_angle)
                                                    : def_.stiffness * (anchor - finger);
    if (law.contacts == ContactForce::sum) {
        // Seed 002 §2.3, the sum over contact pairs: every surface the finger has entered pushes
        // on its own, k d_i n_i, d_i being the finger's depth behind that surface's c-space piece
        // along the piece's normal n_i (the minimum distance of seed 002 eq. 3). As in the seed a
        // pair is traced across its segment and the adjacent ones, so pieces of the same or
        // adjacent segments are one pair; only separate surfaces (a valley's two sides) add up.
        // Each pair's penetration is purely normal, so the ellipsoid acts with k_normal. The
        // summed force has no tangential part to hold, so the stiction point follows the proxy.
        const double k = law.model == ForceModel::ellipsoid ? law.k_normal : def_.stiffness;
        const auto same_pair = [&](int piece_a, int piece_b) {
            const int a = pieces_[static_cast<std::size_t>(piece_a)].segment;
            const int b = pieces_[static_cast<std::size_t>(piece_b)].segment;
            const EnvSegment& sa = env_->segments[static_cast<std::size_t>(a)];
            return a == b || sa.prev == b || sa.next == b;
        };
        const auto pair_force = [&](const CPiece& piece) {
            return k * std::max(0.0, -piece_signed_distance(piece, finger)) * piece_normal_at(piece, finger);
        };
        if (active_count_ == 2 && !same_pair(active_[0], active_[1])) {
            // The proxy rests on two separate surfaces: each pushes by its own depth.
            force = pair_force(pieces_[static_cast<std::size_t>(active_[0])]) +
                    pair_force(pieces_[static_cast<std::size_t>(active_[1])]);
        } else if (active_count_ >= 1) {
            // One surface under the proxy (k times the proxy's depth, as the spring), plus the
            // nearest other surface the finger has crossed before the proxy reaches it: it joins at
            // d = 0, so the force stays continuous when the proxy arrives there later. A piece the
            // proxy is behind (a thin wall's far face) was never entered: no pop-through.
            force = k * (proxy - finger);
            int other = -1;
            double other_d = std::numeric_limits<double>::infinity();
            for (int i = 0; i < static_cast<int>(pieces_.size()); ++i) {
                const CPiece& piece = pieces_[static_cast<std::size_t>(i)];
                const double d = -piece_signed_distance(piece, finger);
                if (d <= 0.0 || d >= other_d || same_pair(i, active_[0])) continue;
                if (active_count_ == 2 && same_pair(i, active_[1])) continue;
                // proxy_ is the walk's proxy, on the pieces (out_.proxy may sit up to the arc
                // spline's tolerance off them after refinement onto a true curve).
                if (piece_signed_distance(piece, proxy_) < -kOnTolerance) continue;
                if (piece_foot(piece, finger).clamped) continue;  // beyond its extent
                if (!contour_leaves_pad_between(pieces_[static_cast<std::size_t>(active_[0])].segment,
                                                piece.segment, finger))
                    continue;  // one overlap with the pad, not a second surface
                other = i;
                other_d = d;
            }
            if (other >= 0) force += pair_force(pieces_[static_cast<std::size_t>(other)]);
        }
        anchor = proxy;
        stiction_ = proxy;
    }
    if (law.damping > 0.0 && dt > 0.0 && previous_depth_ > 0.0) {
        force += law.damping * ((depth - previous_depth_) / dt) * n;
        const double fn = glm::dot(force, n);
        if (fn < 0.0) force -= fn * n;  // damping may soften the push, never pull the finger in
    }
    previous_depth_ = depth;
    const double magnitude = glm::length(force);
    if (magnitude > def_.max_force) force *= def_.max_force / magnitude;
    out_.force = force;
    out_.anchor = anchor;
}

// ---- contact_location_of_contacts ------------------------------------------------------------------
// l_d from the contacts of this tick: their centroid (seed 000), or under least_displacement the
// contact nearest the previous l_d (seed 002: the roller stays with the contact it is on, and moves
// only when a single contact remains elsewhere).
double Proxy::contact_location_of_contacts(double previous_l_d) const {
    if (out_.contact_count == 0) return 0.0;
    if (def_.contact_rule == ContactRule::least_displacement) {
        double best = out_.contacts[0].l;
        for (int i = 1; i < out_.contact_count; ++i)
            if (std::abs(out_.contacts[i].l - previous_l_d) < std::abs(best - previous_l_d)) best = out_.contacts[i].l;
        return best;
    }
    double sum = 0.0;
    for (int i = 0; i < out_.contact_count; ++i) sum += out_.contacts[i].l;
    return sum / out_.contact_count;
}

// ---- refine_on_curves ---------------------------------------------------------------------------
// Curves reach the walk as arc splines within 1e-10 m, good for finding where the proxy rests but
// with normals off by up to ~1e-7 rad, which would put l a few nm off and could report one touch as
// two (on neighbouring arcs). Here contacts on a curve are re-solved on the exact Bezier: the same
// touch is merged, a single contact is moved onto the exact offset (interior) or translated (pad
// end) curve, and every interior contact takes its normal from the exact foot point. Only the
// output moves: the walk keeps its own proxy on the arc spline, where its next tick starts.
namespace {

// Newton stops once a step moves the foot by at most this (m). Near the root, (B(s) - q) . B'(s)
// carries the rounding of coordinates (~1e-17 m at 0.1 m from the origin), so the steps wander
// over tens of ulps of s without settling: the old rule (|ds| <= 1e-17, i.e. an exact fixed point)
// ran all 12 iterations in 72 % of seed 002's calls, a twentieth of a simulated trial's time, to
// move the foot by ~1e-17 m. A femtometre is eight orders below kExactCurveTolerance.
constexpr double kFootStep = 1e-15;

// Foot of q on the curve near parameter s (Newton on (B(s) - q) . B'(s) = 0, kept in [0, 1]).
double local_foot(const Bezier& b, Vec2 q, double s) {
    for (int k = 0; k < 12; ++k) {
        const Vec2 d1 = bezier_derivative(b, s);
        const Vec2 r = bezier_point(b, s) - q;
        const double f = glm::dot(r, d1);
        const double df = glm::dot(d1, d1) + glm::dot(r, bezier_second_derivative(b, s));
        if (!(std::abs(df) > 0.0)) break;
        const double next = std::clamp(s - f / df, 0.0, 1.0);
        const bool settled = std::abs(next - s) * glm::length(d1) <= kFootStep;
        s = next;
        if (settled) break;
    }
    return s;
}

// Free-side unit normal of the curve at s (solid on the right of travel); zero at a cusp.
Vec2 curve_normal(const Bezier& b, double s) {
    const Vec2 d = bezier_derivative(b, s);
    const double len = glm::length(d);
    return len > 0.0 ? perp_left(d) / len : Vec2{0.0};
}

// How far (m) a refinement may move the proxy: the arc spline is within kExactCurveTolerance of
// the curve, so anything much larger means Newton found another branch; keep the walk's answer.
constexpr double kMaxRefinement = 100.0 * kExactCurveTolerance;
// Contacts on one curve closer than this (m) are one touch.
constexpr double kSameTouchDistance = 1e-3;

}  // namespace

void Proxy::refine_on_curves(Vec2 goal) {
    auto curve_of = [&](const ProxyContact& c) { return env_->segments[static_cast<std::size_t>(c.segment)].curve; };
    bool any = false;
    for (int i = 0; i < out_.contact_count; ++i) any = any || curve_of(out_.contacts[i]) >= 0;
    if (!any) return;
    // The same touch seen on two neighbouring arcs of one curve: keep one. The arc spline wiggles
    // by up to kExactCurveTolerance about the curve, enough for a pad whose radius is close to the
    // curve's to rest on two arcs a fraction of a millimetre apart; touches closer than 1 mm on one
    // curve are one contact patch.
    for (int i = 0; i < out_.contact_count; ++i) {
        for (int j = i + 1; j < out_.contact_count;) {
            const ProxyContact& a = out_.contacts[i];
            const ProxyContact& b = out_.contacts[j];
            const bool same = curve_of(a) >= 0 && curve_of(a) == curve_of(b) && a.source == b.source &&
                              glm::length(a.point - b.point) <= kSameTouchDistance;
            if (!same) { ++j; continue; }
            for (int k = j; k + 1 < out_.contact_count; ++k) {
                out_.contacts[k] = out_.contacts[k + 1];
                contact_pieces_[k] = contact_pieces_[k + 1];
            }
            --out_.contact_count;
        }
    }
    const double R = def_.finger.radius;
    if (out_.contact_count == 2) refine_corner();
    for (int i = 0; i < out_.contact_count; ++i) {
        ProxyContact& c = out_.contacts[i];
        const int ci = curve_of(c);
        if (ci < 0) continue;
        const Bezier& b = env_->curves[static_cast<std::size_t>(ci)];
        const double s0 = bezier_nearest(b, c.point).s;
        const bool interior = c.source != CPiece::Source::endpoint;
        // The pad's concave side on a curve: the arc spline's piece stands (within
        // kExactCurveTolerance); the exact re-solve below is for the pad's outer side.
        if (c.source == CPiece::Source::vertex_inner || c.source == CPiece::Source::arc_inner) continue;
        if (out_.contact_count == 1) {
            // One contact: the proxy is the exact nearest point of the c-space curve to the finger.
            if (interior) {
                const double s = local_foot(b, goal, s0);
                const Vec2 n = curve_normal(b, s);
                const Vec2 refined = bezier_point(b, s) + R * n;
                if (glm::length(n) > 0.0 && glm::length(refined - proxy_) <= kMaxRefinement) out_.proxy = refined;
            } else {
                const Vec2 u = unit_at(pad_mid_angle(phi_) + c.l / R);  // the pad end's direction
                const double s = local_foot(b, goal + R * u, s0);
                const Vec2 refined = bezier_point(b, s) - R * u;
                if (glm::length(refined - proxy_) <= kMaxRefinement) {
                    out_.proxy = refined;
                    c.point = bezier_point(b, s);
                }
                continue;
            }
        }
        if (!interior) continue;
        const double s = local_foot(b, out_.proxy, s0);
        const Vec2 n = curve_normal(b, s);
        if (glm::length(n) <= 0.0) continue;
        c.point = bezier_point(b, s);
        c.l = contact_location_at(def_.finger, phi_, angle_of(-n));
    }
}

// Two contacts, at least one on a curve: the proxy is where the two exact c-space curves cross.
// Each contact's c-space curve is parametrised exactly (a line or circle piece as it is; a curve's
// interior contact as the offset B(s) + R n(s); a pad end on a curve as B(s) - R u) and the
// crossing near the walk's corner is found by Newton's method on C1(p1) - C2(p2) = 0.
void Proxy::refine_corner() {
    struct Param {
        const CPiece* piece = nullptr;
        const Bezier* curve = nullptr;
        Vec2 pad_end{0.0};  // R u for a pad end on a curve
        bool interior = true;
        double p = 0.0;
    };
    const double R = def_.finger.radius;
    Param k[2];
    bool any_curve = false;
    for (int i = 0; i < 2; ++i) {
        const ProxyContact& c = out_.contacts[i];
        k[i].piece = &pieces_[static_cast<std::size_t>(contact_pieces_[i])];
        const int ci = env_->segments[static_cast<std::size_t>(c.segment)].curve;
        const bool inner = c.source == CPiece::Source::vertex_inner || c.source == CPiece::Source::arc_inner;
        if (ci >= 0 && !inner) {  // an inner contact keeps its arc spline piece (refine_on_curves)
            any_curve = true;
            k[i].curve = &env_->curves[static_cast<std::size_t>(ci)];
            k[i].interior = c.source != CPiece::Source::endpoint;
            k[i].pad_end = R * unit_at(pad_mid_angle(phi_) + c.l / R);
            k[i].p = bezier_nearest(*k[i].curve, c.point).s;
        } else {
            k[i].p = piece_param(*k[i].piece, proxy_);
        }
    }
    if (!any_curve) return;
    // Point and derivative of a contact's c-space curve at parameter p.
    auto eval = [&](const Param& q, double p, Vec2& d) -> Vec2 {
        if (q.curve) {
            const Vec2 b1 = bezier_derivative(*q.curve, p);
            if (!q.interior) {
                d = b1;
                return bezier_point(*q.curve, p) - q.pad_end;
            }
            const Vec2 b2 = bezier_second_derivative(*q.curve, p);
            const double len = glm::length(b1);
            const Vec2 dt = (b2 * (len * len) - b1 * glm::dot(b1, b2)) / (len * len * len);  // d(unit tangent)/ds
            d = b1 + R * perp_left(dt);
            return bezier_point(*q.curve, p) + R * perp_left(b1 / len);
        }
        const CPiece& pc = *q.piece;
        if (pc.kind == CPiece::Kind::line) {
            d = pc.dir;
            return pc.a + p * pc.dir;
        }
        const Vec2 u = unit_at(pc.span.start + p);
        d = pc.radius * perp_left(u);
        return pc.center + pc.radius * u;
    };
    double p0 = k[0].p, p1 = k[1].p;
    Vec2 x{0.0};
    bool converged = false;
    for (int it = 0; it < 12; ++it) {
        Vec2 d0, d1;
        const Vec2 a = eval(k[0], p0, d0), b = eval(k[1], p1, d1);
        const Vec2 f = a - b;
        x = a;
        if (glm::length(f) <= 1e-13) { converged = true; break; }
        // Solve [d0, -d1] (dp0, dp1) = -f by Cramer's rule.
        const double det = cross(d0, -d1);
        if (!(std::abs(det) > 1e-300)) break;
        p0 += cross(-f, -d1) / det;
        p1 += cross(d0, -f) / det;
        if (!std::isfinite(p0) || !std::isfinite(p1)) break;
    }
    if (!converged || glm::length(x - proxy_) > kMaxRefinement) return;
    out_.proxy = x;
    for (int i = 0; i < 2; ++i) {
        ProxyContact& c = out_.contacts[i];
        if (k[i].curve == nullptr) {
            c.point = piece_contact_point(*k[i].piece, def_.finger, x);
            c.l = piece_contact_location(*k[i].piece, def_.finger, phi_, x);
        } else if (!k[i].interior) {
            c.point = bezier_point(*k[i].curve, i == 0 ? p0 : p1);
        }
        // Interior contacts on curves take their exact foot in refine_on_curves' loop.
    }
}

// ---- anticipate ---------------------------------------------------------------------------------
// Free space: drive l_d to the contact the finger would make with the nearest c-space piece,
// found by projecting x_f perpendicularly onto it (seed 000 §3.2, Fig. 6).
void Proxy::anticipate(Vec2 finger, double phi) {
    if (env_->segments.empty()) return;
    const double R = def_.finger.radius;
    if (def_.use_index) {
        // Nearest first through the index: a segment's pieces are built only if its node's lower
        // bound does not exceed the best distance so far. The winner is the first piece at the
        // least distance in (segment, piece) order: the one the search of every segment below
        // finds, bit for bit. With a budget the search may end ticks later (ProxyDef).
        const int budget = std::max(def_.anticipation_budget, 0);
        bool seeded = false;  // this tick began a search and asked the last one's nearest segment
        // Exact mode: the last search's nearest few segments may answer alone (hold_). Why: seed
        // 002's hand hovers a fifth of its ticks over 2 mm segments, and each tick's search walked
        // about 50 of the tree's nodes to prove that its seed still won.
        // Where holds keep failing (a finger moving more in a tick than the few segments' lead
        // over the rest: dense contours, where the few nearest are also costly to gather), a
        // hold is neither asked nor gathered for 1, 3, 7, 15 ticks after each failure in a row.
        // A tick whose hold failed searches without gathering the next: the failed hold's asks
        // and a gathering search's extra ones on one tick made the slowest hover ticks of 100 to
        // 1,000-segment scenes (p99.9 twice the plain search's); the next free tick gathers.
        bool held = false;
        const bool may_hold = budget == 0 && hold_skip_ == 0;
        bool gather = may_hold;
        if (budget == 0 && hold_skip_ > 0) --hold_skip_;
        if (may_hold && hold_.valid && std::abs(wrap_pi(phi - hold_.phi)) <= kHoldTurn) {
            held = held_anticipation(finger, phi);
            if (held) {
                ++hold_.uses;
            } else {
                gather = false;
                hold_.valid = false;
                if (hold_.uses == 0) note_hold_failure();  // (one that served some ticks did its job)
                else hold_failures_ = 0;
            }
        }
        if (held) {
            // (the answer is set: published below as a finished search's)
        } else if (budget == 0 || !search_.active || search_phi_ != phi) {
            const PadFrame& pad = pad_frame(phi);
            const bool ends = pad_has_endpoints(def_.finger);
            const Vec2 end_points[2] = {finger + R * pad.end_dir[0], finger + R * pad.end_dir[1]};
            // Outer pieces press along normals opposite the pad's span (cspace.cpp).
            const NormalCone outer_normals{wrap_2pi(pad.span.start + kPi), pad.span.width};
            env_->tree.start_pad_search(search_, finger, R, ends, end_points, ends ? 2 : 0, outer_normals);
            search_phi_ = phi;
            const int last_winner = search_best_segment_;
            search_best_segment_ = -1;
            search_best_foot_ = Vec2{0.0};
            search_started_ = ticks_;
            search_seed_ = -1;
            search_best_distance_ = std::numeric_limits<double>::infinity();
            collect_hold_ = gather;
            out_.work.anticipation_gathered = gather;
            hold_asks_ = 0;
            hold_motion_ = glm::length(last_finger_motion_);
            near_count_ = 0;
            search_floor_ = std::numeric_limits<double>::infinity();
            // The last search's nearest segment, asked first: its distance now is within the
            // finger's motion of the answer, so from the start the depth-first search skips every
            // node whose bound is beyond it. Unseeded, the best shrank leaf by leaf: 1 cm above a
            // valley of the pad's own shape, high nodes hold the pad's ends (bound 0) and the
            // search asked 5,000 segments a tick (1.0-1.4 ms at 100,000 segments), where seeded it
            // asks 110-250. The answer cannot change: that segment is asked again in its turn, and
            // a tie still goes to the lowest segment.
            // (A budget of 1 asks nothing more: the seed would make it 2.)
            // With no search before (the first free tick), the segment nearest the finger is
            // asked first instead: its pieces lie within R of it, so its distance less R bounds
            // the others' (ask_anticipation) and few are built. Unseeded, the first tick over a
            // rough floor built 248 segments' pieces (1.1 ms at 100,000 segments).
            if (budget != 1) {
                const int seed = last_winner >= 0 ? last_winner : nearest_segment(finger);
                if (seed >= 0) {
                    ask_anticipation(seed);
                    search_seed_ = seed;
                    seeded = true;
                }
            }
        }
        // A spread search's seed is one of its tick's budget (budget - 1 >= 1 here).
        if (held || continue_anticipation(seeded && budget > 1 ? budget - 1 : budget)) {
            if (collect_hold_ && !held) {
                // The next ticks' hold: this search's nearest few, and under every other segment
                // the least of the tree's pruned bounds, the segments answered by bound, and the
                // distances of those asked but not held.
                hold_.valid = near_count_ > 0;
                hold_.uses = 0;
                hold_.finger = search_.p;
                hold_.phi = search_phi_;
                hold_.count = std::min(near_count_, kHeldSegments);
                for (int k = 0; k < hold_.count; ++k) hold_.ids[static_cast<std::size_t>(k)] = near_segment_[static_cast<std::size_t>(k)];
                hold_.floor = std::min(search_.pruned, search_floor_);
                if (near_count_ > kHeldSegments) hold_.floor = std::min(hold_.floor, near_distance_[kHeldSegments]);
            }
            if constexpr (kValidation)
                validate_anticipation(held ? finger : search_.p, pad_frame(search_phi_), search_best_segment_, search_best_foot_);
            anticipated_.valid = search_best_segment_ >= 0;
            anticipated_.searched_at = search_started_;
            if (anticipated_.valid) {
                anticipated_.l_d = piece_contact_location(anticipated_piece_, def_.finger, search_phi_, search_best_foot_);
                anticipated_.point = piece_contact_point(anticipated_piece_, def_.finger, search_best_foot_);
            }
        }
        out_.work.anticipation_searching = search_.active;
        out_.work.anticipation_held = held;
        out_.anticipating = anticipated_.valid;
        if (anticipated_.valid) {
            out_.l_d = anticipated_.l_d;
            out_.anticipated_point = anticipated_.point;
            out_.work.anticipation_behind = static_cast<int>(std::min<std::int64_t>(ticks_ - anticipated_.searched_at, 1 << 30));
        } else {
            // Nothing found yet since the last contact: l_d stays where the contact left it.
            out_.l_d = anticipated_.l_d;
            out_.work.anticipation_behind = -1;
        }
        return;
    }
    // Without the index (the brute-force reference the tests compare with): every segment.
    const int nearest_id = nearest_segment(finger);
    const double nearest_distance = distance_to_segment(env_->segments[static_cast<std::size_t>(nearest_id)], finger);  // m
    // Every point of a segment has a c-space point within R of it (the pad's end, at least, can
    // touch it there), and every piece lies within R of its segment: the nearest piece is between
    // nearest_distance - R and nearest_distance + R away, and the nearest segment's own pieces give
    // a tighter upper bound. Gathering every segment within nearest_distance + 2R (a box) is exact
    // but, 1 cm above a densely sampled contour, builds pieces for thousands of segments (5 ms a
    // tick at 100,000 segments). Instead gather only what can come within a short reach, as the
    // motion does (normal cones, pad-end views): a piece found within that reach is the nearest
    // of all. If none is, a second gather reaches to the upper bound, which is exact.
    const PadFrame& pad = pad_frame(phi);
    // (Its own scratch list: pieces_ keeps what build_pieces built, for the next build to copy.)
    nearest_pieces_.clear();
    append_cspace_pieces(*env_, nearest_id, pad, nearest_pieces_);
    double upper = nearest_distance + R + kOnTolerance;  // m
    for (const CPiece& piece : nearest_pieces_) upper = std::min(upper, glm::length(piece_foot(piece, finger).point - finger));
    upper += kOnTolerance;
    const double first_reach = std::max(0.0, nearest_distance - R) + kAnticipationReachMargin;
    for (const double reach : {std::min(first_reach, upper), upper}) {
        gather_within_reach(finger, phi, reach);
        build_pieces(phi);
        double best = std::numeric_limits<double>::infinity();
        const CPiece* nearest = nullptr;  // the first piece at the least distance
        Vec2 nearest_foot{0.0};
        for (const CPiece& piece : pieces_) {
            const PieceFoot foot = piece_foot(piece, finger);
            const double d = glm::length(foot.point - finger);
            if (d >= best) continue;
            best = d;
            nearest = &piece;
            nearest_foot = foot.point;
        }
        // Contact location and point of the winner only (over a dense valley thousands of pieces
        // improve on each other in turn).
        out_.anticipating = nearest != nullptr;
        if (nearest) {
            out_.l_d = piece_contact_location(*nearest, def_.finger, phi, nearest_foot);
            out_.anticipated_point = piece_contact_point(*nearest, def_.finger, nearest_foot);
        }
        if (best <= reach) return;
    }
}

int Proxy::nearest_segment(Vec2 p) const {
    int nearest = -1;
    double least = std::numeric_limits<double>::infinity();  // m
    env_->tree.nearest_distance(p, [&](int i) {
        const double d = distance_to_segment(env_->segments[static_cast<std::size_t>(i)], p);
        if (d < least) least = d, nearest = i;
        return d;
    });
    return nearest;
}

bool Proxy::continue_anticipation(int budget) {
    return env_->tree.continue_pad_search(search_, budget, [&](int id) { return ask_anticipation(id); });
}

double Proxy::ask_anticipation(int id) {
    const Vec2 finger = search_.p;
    // Every point of a segment's pieces is a place of the finger where the pad touches the
    // segment, so lies within R of it: no piece is nearer the finger than the segment's distance
    // less R (an arc: than its circle's distance less R). A segment that bound puts beyond the best so far (by far more than any rounding)
    // cannot win, and is answered without building its pieces (its answer, +inf, leaves the
    // search's best as it is). Why: the tree's bounds are boxes, loose by a segment's own size;
    // hovering over a rough floor (100,000 segments 4 um long, jittered by 20 um) a few hundred
    // segments' boxes tied within that looseness, each built and asked: 0.3 ms a tick.
    // (An arc's bound is its whole circle's distance: no angle to take, an atan2 a segment.)
    const EnvSegment& segment = env_->segments[static_cast<std::size_t>(id)];
    const double to_segment = segment.kind == EnvSegment::Kind::line
                                  ? distance_to_segment(segment, finger)
                                  : std::abs(glm::length(finger - segment.center) - segment.radius);  // m
    const double beyond = to_segment - def_.finger.radius;
    if (beyond > search_.best + kOnTolerance) {
        search_floor_ = std::min(search_floor_, beyond);
        return std::numeric_limits<double>::infinity();
    }
    // The seed again, in its turn: the same pieces at the same finger and angle give the same
    // distances, none below the best (which already holds them) nor a tie it would win (its own
    // segment's), and the search's min with any answer keeps the best: nothing to ask.
    if (id == search_seed_) return std::numeric_limits<double>::infinity();
    ++out_.work.anticipated_segments;
    const NearestPiece nearest = nearest_asked_piece(id, finger);
    const double least = nearest.distance;  // m
    if (nearest.piece && (least < search_best_distance_ || (least == search_best_distance_ && id < search_best_segment_))) {
        search_best_distance_ = least;
        search_best_segment_ = id;
        search_best_foot_ = nearest.foot;
        anticipated_piece_ = *nearest.piece;
        if (!collect_hold_) search_.best = least;
    }
    if (!collect_hold_) return least;
    // Exact mode gathers the next ticks' hold: the tree prunes beyond the (kHeldSegments + 1)-th
    // nearest so far instead of the nearest, so the few nearest are all asked (the answer is the
    // same: every segment that could win or tie is still asked, and more).
    // ... at most kHoldAsks segments: where more lie that close (a dense contour), the search
    // goes back to pruning beyond the nearest, and makes no hold.
    // ... and none once the few nearest lead the next by less than twice the finger's last motion
    // (the hold would fail at the next tick: a dense contour, where ties crowd).
    note_asked(id, least);
    const bool hopeless = near_count_ > kHeldSegments && near_distance_[kHeldSegments] - near_distance_[0] <= 2.0 * hold_motion_;
    if (++hold_asks_ > kHoldAsks || hopeless) {
        collect_hold_ = false;
        near_count_ = 0;
        note_hold_failure();
        search_.best = search_best_distance_;
        return least;
    }
    const double kth = near_count_ > kHeldSegments ? near_distance_[kHeldSegments] : std::numeric_limits<double>::infinity();
    search_.best = std::min(search_.best, kth);
    return kth;
}

void Proxy::note_hold_failure() {
    hold_failures_ = std::min(hold_failures_ + 1, kHoldFailures);
    hold_skip_ = (1 << hold_failures_) - 1;
}

void Proxy::note_asked(int id, double least) {
    constexpr int kKept = kHeldSegments + 1;
    for (int k = 0; k < near_count_; ++k)
        if (near_segment_[static_cast<std::size_t>(k)] == id) return;  // (asked again: the same distance)
    if (near_count_ == kKept) {
        if (!(least < near_distance_[kKept - 1])) {
            search_floor_ = std::min(search_floor_, least);
            return;
        }
        search_floor_ = std::min(search_floor_, near_distance_[kKept - 1]);  // drops out of the few
        --near_count_;
    }
    int k = near_count_++;
    for (; k > 0 && near_distance_[static_cast<std::size_t>(k - 1)] > least; --k) {
        near_distance_[static_cast<std::size_t>(k)] = near_distance_[static_cast<std::size_t>(k - 1)];
        near_segment_[static_cast<std::size_t>(k)] = near_segment_[static_cast<std::size_t>(k - 1)];
    }
    near_distance_[static_cast<std::size_t>(k)] = least;
    near_segment_[static_cast<std::size_t>(k)] = id;
}

bool Proxy::held_anticipation(Vec2 finger, double phi) {
    if (!hold_.valid) return false;
    // How far the finger moved, and how far any point of the pad moved as it turned (its chord):
    // a segment's distance is the finger's distance to the set of places where the pad meets
    // it, which the turn moves by at most the chord.
    const double turn = std::abs(wrap_pi(phi - hold_.phi));                      // rad
    const double chord = 2.0 * def_.finger.radius * std::sin(0.5 * turn) * (1.0 + 1e-9);  // m
    const double moved = glm::length(finger - hold_.finger) + chord;             // m
    // The held segments at this finger and angle, as ask_anticipation asks them: the first piece
    // at the least distance, ties to the lowest segment.
    search_phi_ = phi;  // (asked_pieces builds at this tick's angle)
    double best = std::numeric_limits<double>::infinity();  // m
    int best_segment = -1;
    Vec2 best_foot{0.0};
    // A copy, not a pointer into the ask cache's pool: asking the next held segment may start
    // the pool over (a full cache) and write another segment's pieces where this one was.
    CPiece best_piece{};
    for (int k = 0; k < hold_.count; ++k) {
        const int id = hold_.ids[static_cast<std::size_t>(k)];
        const NearestPiece nearest = nearest_asked_piece(id, finger);
        if (nearest.piece && (nearest.distance < best || (nearest.distance == best && id < best_segment))) {
            best = nearest.distance;
            best_segment = id;
            best_foot = nearest.foot;
            best_piece = *nearest.piece;
        }
    }
    out_.work.anticipated_segments += hold_.count;
    // Every other segment's pieces lie at least floor - moved away: strictly beyond the best (by
    // far more than any rounding of the bounds or distances), none can win or tie.
    if (!(best_segment >= 0 && best < hold_.floor - moved - kOnTolerance)) return false;
    search_best_distance_ = best;
    search_best_segment_ = best_segment;
    search_best_foot_ = best_foot;
    anticipated_piece_ = best_piece;
    search_started_ = ticks_;
    return true;
}

Proxy::NearestPiece Proxy::nearest_asked_piece(int id, Vec2 finger) {
    int count = 0;
    const CPiece* pieces = asked_pieces(id, count);
    NearestPiece nearest;
    nearest.distance = std::numeric_limits<double>::infinity();
    for (int k = 0; k < count; ++k) {
        const PieceFoot foot = piece_foot(pieces[k], finger);
        const double d = glm::length(foot.point - finger);  // m
        if (d < nearest.distance) nearest = NearestPiece{d, &pieces[k], foot.point};
    }
    return nearest;
}

const CPiece* Proxy::asked_pieces(int id, int& count) {
    if (ask_cache_size_ > 0 && ask_cache_phi_ != search_phi_) ask_cache_size_ = 0;  // another angle
    for (int k = 0; k < ask_cache_size_; ++k) {
        const AskedSegment& e = ask_cache_[static_cast<std::size_t>(k)];
        if (e.segment == id) {
            count = e.count;
            return ask_pool_.data() + e.first;
        }
    }
    const PadFrame& pad = pad_frame(search_phi_);
    if (ask_cache_size_ == 0) ask_pool_.clear();
    // Full (entries, or no room left for a segment's most pieces): start over.
    if (ask_cache_size_ == kAskCache || ask_pool_.size() + kMostPiecesPerSegment > ask_pool_.capacity()) {
        ask_cache_size_ = 0;
        ask_pool_.clear();
    }
    const std::size_t first = ask_pool_.size();
    append_cspace_pieces(*env_, id, pad, ask_pool_);
    ask_cache_phi_ = search_phi_;
    ask_cache_[static_cast<std::size_t>(ask_cache_size_++)] = {id, static_cast<int>(first), static_cast<int>(ask_pool_.size() - first)};
    count = static_cast<int>(ask_pool_.size() - first);
    return ask_pool_.data() + first;
}

// ---- validation ---------------------------------------------------------------------------------
// Every segment's pieces, nearest first in (segment, piece) order: what the index's nearest-first
// search must return (its lower bounds may only skip segments that cannot win). Scenes up to
// kValidateAnticipationSegments only: the search is the index's point at 100,000 segments, and
// every tick of a test there would take milliseconds.
void Proxy::validate_anticipation(Vec2 finger, const PadFrame& pad, int best_segment, Vec2 best_foot) {
    constexpr int kValidateAnticipationSegments = 4096;
    const int count = static_cast<int>(env_->segments.size());
    if (count > kValidateAnticipationSegments) return;
    double best = std::numeric_limits<double>::infinity();  // m
    int segment = -1;
    Vec2 foot{0.0};
    for (int id = 0; id < count; ++id) {
        nearest_pieces_.clear();
        append_cspace_pieces(*env_, id, pad, nearest_pieces_);
        for (const CPiece& piece : nearest_pieces_) {
            const Vec2 point = piece_foot(piece, finger).point;
            const double d = glm::length(point - finger);
            if (d < best) best = d, segment = id, foot = point;
        }
    }
    CONTACTLAB_VALIDATE(segment == best_segment && foot == best_foot,
                        "anticipation's nearest-first search finds the piece a search of every segment finds");
    // ... and the piece it kept (l_d is read from it) is that piece, not a stale copy.
    CONTACTLAB_VALIDATE(best_segment < 0 || piece_foot(anticipated_piece_, finger).point == best_foot,
                        "anticipation keeps the piece its nearest foot lies on");
}

}  // namespace contactlab
