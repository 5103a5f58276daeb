// Every culler's options as plain data, in one header the rest of the program may see (the
// scenario parser, sweeps, the tuner) without seeing any culler's internals. Each struct's
// isValid() is the one definition of "valid": parsers and sweeps report its message.
#pragma once

#include <cstdint>
#include <string>

namespace occsim {

// Kovalčík & Sochor, "Occlusion Culling with Statistically Optimized Occlusion Queries", WSCG
// 2005, section 3: BASE_TIME and the decay curve of CalcNodeAction, and the two-queue traversal.
struct StatisticalOptions {
    double base_time_s = 2.0 / 3.0;      // BASE_TIME
    double decay_a = 2.0;                // a in BASE_TIME * (a - b^occ_num)
    double decay_b = 0.5;                // b in BASE_TIME * (a - b^occ_num)
    uint32_t history_length = 8;         // query results remembered per node (1..32)
    double max_statistics_age_s = 2.0;   // older statistics are ignored: query again
    uint32_t queries_before_restart = 20;  // return to the queue start after this many queries

    bool isValid(std::string* error) const;
};

// Bittner, Wimmer, Piringer & Purgathofer, "Coherent Hierarchical Culling: Hardware Occlusion
// Queries Made Useful", Eurographics 2004, "Further Optimizations". The paper's approximate
// visibility (n_vp) is the pixel threshold of ApproximationOptions, shared by every culler.
struct ChcOptions {
    // t_av: frames a leaf found visible is assumed visible without a query. 0 = every previously
    // visible leaf is queried every frame (the basic algorithm).
    uint32_t visible_frames_skip = 0;

    bool isValid(std::string* error) const;
};

// Mattausch, Bittner & Wimmer, "CHC++: Coherent Hierarchical Culling Revisited", Eurographics
// 2008, sections 4 (queues), 5.1 (multiqueries), 5.2 (randomised sampling) and 6 (tight bounds).
struct ChcppOptions {
    // n_av: frames a node found visible is assumed visible (no query) before the next test.
    // On the default teapot scenario (llvmpipe), n_av = 0 / 2 / 5 / 10 gives 280 / 176 / 146 /
    // 125 queries and 1004 / 1044 / 1126 / 1197 drawn objects per frame: 2 trades about even.
    uint32_t visible_frames_skip = 2;
    // Previously invisible nodes collected before a batch of queries is issued.
    uint32_t batch_size = 50;
    // Group previously invisible nodes into multiqueries (false: one query per node).
    bool multiqueries = true;
    // Query a node with its descendants' boxes this many levels down; 0 = its own box. On the
    // default teapot scenario 2 saves a few queries and drawn objects at every n_av.
    uint32_t tight_bounds_depth = 2;
    // Seeds the randomised first re-test of nodes that turned visible.
    uint64_t seed = 1;

    bool isValid(std::string* error) const;
};

// The per-object asynchronous scheme of the PURE engine notes ("Simple Pseudo-code"), with the
// re-test rule of the ARB_occlusion_query specification.
struct AsyncOptions {
    // N: a visible object is queried again this many frames after its last query. 1 = every frame.
    uint32_t retest_interval_frames = 5;

    bool isValid(std::string* error) const;
};

// Two ways to trade image error for time, for any culler that issues queries (applied by
// ApproximateDevice, culling/approximate_device.h):
// - threshold_pixels: a query passing at most this many samples counts as occluded (the CHC
//   paper's approximate visibility, n_vp);
// - stale_results: a result not ready when the culler asks for it is taken from the last frame's
//   query on the same boxes instead of waited for.
// Both make conservative cullers approximate; with both off nothing changes.
struct ApproximationOptions {
    uint32_t threshold_pixels = 0;
    bool stale_results = false;

    bool active() const { return threshold_pixels > 0 || stale_results; }
};

struct CullerOptions {
    StatisticalOptions statistical;
    ChcOptions chc;
    ChcppOptions chcpp;
    AsyncOptions async;
    ApproximationOptions approximation;

    // The first invalid member's message.
    bool isValid(std::string* error) const;
};

}  // namespace occsim
