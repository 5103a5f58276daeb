// `occsim why`: answers in words from a run's objects.sqlite. For one object (by index or name),
// at one frame or over the run: each configuration's decision and the reason its culler gave
// ("frame 178, async: not drawn: the query issued at frame 176 (2 frames before) answered
// occluded; ground truth sees 412 px"); or the objects a configuration drew while hidden, or
// every object it missed. docs/objects.md shows the wording of every reason kind.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "occsim/culling/contract/decision_log.h"
#include "sim/record/object_queries.h"

namespace occsim {

struct WhyRequest {
    std::filesystem::path run;  // the run folder
    std::string object;         // an index or a name (--object); empty with overdraw or missed
    std::optional<uint32_t> frame;
    std::string algo;  // a configuration's label or its algorithm's name; empty: every one
    bool overdraw = false;
    bool missed = false;
    uint32_t limit = 20;  // over-drawn objects listed per configuration
    // Whose decisions (--view): the camera's (the left eye's in a stereo run culled per eye), the
    // right eye's, or the light view's.
    RecordedView view = RecordedView::Camera;
    bool left_eye = false;  // --view left: the camera's, required to be a stereo run per eye
};

// Throws InputError (one line, naming the flag or file) for a folder without a database, one
// from another version or a damaged one, an unknown object or configuration, a frame outside the
// run, or flags that do not go together; all of it before any answer.
std::string answerWhy(const WhyRequest& request);

// One decision in words: "drawn: the query issued at frame 12 answered visible (84 samples);
// ground truth sees 80 px". Exposed for tests.
std::string describeDecision(const RecordedDecision& d, RecordedView view = RecordedView::Camera);

}  // namespace occsim
