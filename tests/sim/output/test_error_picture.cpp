// The worst-frame error pictures: error and tie pixels in their own colours, each error pixel
// under a label, every cluster ringed and each missed object labelled; and on a real run, a
// culler that drops a visible object shows error, the miss and its popping, and its worst frame's
// picture marks the errors apart from the ties.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "error_bench.h"
#include "sim/output/error_picture.h"

namespace occsim {
namespace {

// The worst-frame picture: culled | ground truth | ground truth dimmed with error pixels in
// magenta and tie pixels in yellow (docs/error.md).
TEST(ErrorPicture, MarksErrorsAndTiesInTheirOwnColours) {
    const uint32_t w = 3, h = 1;
    ErrorFrame frame;
    frame.culled_rgba.assign(w * h * 4, 30);
    frame.truth_rgba.assign(w * h * 4, 90);
    frame.culled_ids = {1, 2, 0};
    frame.truth_ids = {1, 3, 4};
    frame.differences = {static_cast<uint8_t>(PixelDifference::Same),
                         static_cast<uint8_t>(PixelDifference::Tie),
                         static_cast<uint8_t>(PixelDifference::Error)};
    const std::vector<uint8_t> picture = composeErrorPicture(frame, w, h);
    ASSERT_EQ(picture.size(), size_t{3 * w} * h * 4);
    const uint8_t* marks = picture.data() + 2 * w * 4;
    EXPECT_EQ(marks[0], 30) << "an unchanged pixel is ground truth dimmed";
    EXPECT_EQ(std::vector<uint8_t>(marks + 4, marks + 7),
              std::vector<uint8_t>(kTieColour, kTieColour + 3));
    EXPECT_EQ(std::vector<uint8_t>(marks + 8, marks + 11),
              std::vector<uint8_t>(kErrorColour, kErrorColour + 3));
    frame.differences.pop_back();
    EXPECT_THROW(composeErrorPicture(frame, w, h), std::invalid_argument);
}

// The picture report.md shows: the panels one above the other, each frame pixel a square of
// errorPictureScale() pixels, each panel under a label in black on white.
TEST(ErrorPicture, TheLabelledPictureShowsEachErrorPixelAsASquareUnderALabel) {
    const uint32_t w = 100, h = 2;  // scale 8: the most
    ErrorFrame frame;
    frame.culled_rgba.assign(w * h * 4, 30);
    frame.truth_rgba.assign(w * h * 4, 90);
    frame.culled_ids.assign(w * h, 1);
    frame.truth_ids.assign(w * h, 1);
    frame.differences.assign(w * h, static_cast<uint8_t>(PixelDifference::Same));
    frame.differences[w + 7] = static_cast<uint8_t>(PixelDifference::Error);  // x 7, row 1
    frame.error_pixels = 1;
    const uint32_t scale = errorPictureScale(w);
    ASSERT_EQ(scale, 8u);
    EXPECT_EQ(errorPictureScale(200), 4u);
    EXPECT_EQ(errorPictureScale(4000), 1u);
    const LabelledPicture picture = labelledErrorPicture(frame, w, h, "statistical");
    ASSERT_EQ(picture.rgba.size(), size_t{picture.width} * picture.height * 4);
    const uint32_t panel = (picture.height) / 3;  // label strip + scaled frame
    const uint32_t band = panel - h * scale;
    EXPECT_GT(band, 14u) << "a label strip above every panel";
    EXPECT_GE(picture.width, w * scale);
    // Rows are bottom-up: the last panel (the difference) is at the bottom; its frame row 1
    // (bottom-up, as the frame's) is the upper one of its two scaled rows.
    auto at = [&](uint32_t x, uint32_t y_from_bottom) {
        const uint8_t* p = picture.rgba.data() + (size_t{y_from_bottom} * picture.width + x) * 4;
        return std::vector<uint8_t>(p, p + 3);
    };
    const std::vector<uint8_t> magenta(kErrorColour, kErrorColour + 3);
    int marked = 0;
    for (uint32_t y = 0; y < 2 * scale; ++y) {
        for (uint32_t x = 0; x < w * scale; ++x) marked += at(x, y) == magenta;
    }
    EXPECT_EQ(marked, static_cast<int>(scale * scale)) << "one error pixel, one square";
    for (uint32_t d = 0; d < scale; ++d) {
        EXPECT_EQ(at(7 * scale + d, scale + d), magenta) << d;
    }
    int ink = 0;  // the difference panel's label, in black above it
    for (uint32_t y = 2 * scale; y < 2 * scale + band; ++y) {
        for (uint32_t x = 0; x < picture.width; ++x)
            ink += at(x, y) == std::vector<uint8_t>{0, 0, 0};
    }
    EXPECT_GT(ink, 100) << "a label";
}

// The worst frame's error pixels are found at any size: every cluster of them is ringed, a few
// picture pixels outside it, and every object ground truth shows there is labelled beside it.
TEST(ErrorPicture, EveryClusterOfErrorPixelsIsRingedAndEachMissedObjectLabelled) {
    const uint32_t w = 60, h = 40;  // scale 8
    ErrorFrame frame;
    frame.culled_rgba.assign(w * h * 4, 30);
    frame.truth_rgba.assign(w * h * 4, 90);
    frame.culled_ids.assign(w * h, 1);
    frame.truth_ids.assign(w * h, 1);
    frame.differences.assign(w * h, static_cast<uint8_t>(PixelDifference::Same));
    auto mark = [&](uint32_t x, uint32_t y, uint32_t truth_id) {
        frame.differences[y * w + x] = static_cast<uint8_t>(PixelDifference::Error);
        frame.truth_ids[y * w + x] = truth_id;
    };
    for (uint32_t x = 10; x <= 12; ++x) {  // object 4: 3 x 2 pixels
        mark(x, 5, 5);
        mark(x, 6, 5);
    }
    mark(45, 30, 8);  // object 7: one pixel
    frame.differences[20 * w + 30] = static_cast<uint8_t>(PixelDifference::Tie);
    frame.error_pixels = 7;

    const std::vector<PixelCluster> clusters = errorClusters(frame.differences, w, h);
    ASSERT_EQ(clusters.size(), 2u);
    EXPECT_EQ(clusters[0].pixels, 6u);
    EXPECT_EQ(
        std::vector<uint32_t>({clusters[0].x0, clusters[0].y0, clusters[0].x1, clusters[0].y1}),
        std::vector<uint32_t>({10, 5, 12, 6}));
    EXPECT_EQ(clusters[1].pixels, 1u);
    const std::vector<MissedInFrame> missed = missedObjects(frame, w, h);
    ASSERT_EQ(missed.size(), 2u);
    EXPECT_EQ(missed[0].object, 4u);
    EXPECT_EQ(missed[1].object, 7u);
    EXPECT_EQ(missed[1].where.pixels, 1u);

    const uint32_t scale = errorPictureScale(w);
    ASSERT_EQ(scale, 8u);
    auto greenIn = [](const LabelledPicture& p, uint32_t x0, uint32_t y0, uint32_t x1,
                      uint32_t y1) {
        int n = 0;
        for (uint32_t y = y0; y <= y1; ++y) {
            for (uint32_t x = x0; x <= x1; ++x) {
                const uint8_t* c = p.rgba.data() + (size_t{y} * p.width + x) * 4;
                n += c[0] == kRingColour[0] && c[1] == kRingColour[1] && c[2] == kRingColour[2];
            }
        }
        return n;
    };
    const LabelledPicture picture = labelledErrorPicture(frame, w, h, "async");
    // The difference panel is the bottom one; frame pixel (x, y) covers picture pixels
    // [8x, 8x + 7] x [8y, 8y + 7], rows bottom-up. The one-pixel cluster at (45, 30):
    const uint32_t x0 = 45 * scale, x1 = x0 + scale - 1, y0 = 30 * scale, y1 = y0 + scale - 1;
    EXPECT_EQ(greenIn(picture, x0, y0, x1, y1), 0) << "the ring stands outside the pixel";
    EXPECT_GT(greenIn(picture, x0 - 12, y0, x0 - 1, y1), 0) << "left side";
    EXPECT_GT(greenIn(picture, x1 + 1, y0, x1 + 12, y1), 0) << "right side";
    EXPECT_GT(greenIn(picture, x0, y1 + 1, x1, y1 + 12), 0) << "above";
    EXPECT_GT(greenIn(picture, x0, y0 - 12, x1, y0 - 1), 0) << "below";
    // The larger cluster's ring, on its left.
    EXPECT_GT(greenIn(picture, 10 * scale - 12, 5 * scale, 10 * scale - 1, 7 * scale - 1), 0);
    // The label "#7" beside the ring of object 7, right of it.
    const int label = greenIn(picture, x1 + 13, y0 - 30, x1 + 60, y1 + 30);
    EXPECT_GT(label, 20) << "a label beside the ring";
    // Every error pixel stays magenta, whatever is drawn around it.
    const std::vector<uint8_t> magenta(kErrorColour, kErrorColour + 3);
    int marked = 0;
    for (uint32_t y = 0; y < h * scale; ++y) {
        for (uint32_t x = 0; x < w * scale; ++x) {
            const uint8_t* c = picture.rgba.data() + (size_t{y} * picture.width + x) * 4;
            marked += std::vector<uint8_t>(c, c + 3) == magenta;
        }
    }
    EXPECT_EQ(marked, static_cast<int>(7 * scale * scale));
    // With names, the label says the name too: a longer label.
    std::vector<std::string> names(8);
    names[7] = "statue";
    const LabelledPicture named = labelledErrorPicture(frame, w, h, "async", &names);
    EXPECT_GT(greenIn(named, 0, 0, w * scale - 1, h * scale - 1),
              greenIn(picture, 0, 0, w * scale - 1, h * scale - 1) + 20);
}

// A device that never draws one object: what a culler that wrongly drops it puts on screen.
class DroppingDevice final : public RenderDevice {
  public:
    DroppingDevice(RenderDevice& inner, uint32_t dropped) : inner_(inner), dropped_(dropped) {}
    void drawObject(uint32_t object) override {
        if (object != dropped_) inner_.drawObject(object);
    }
    QueryId issueQuery(std::span<const Aabb> boxes, std::span<const QueryTag> subjects) override {
        return inner_.issueQuery(boxes, subjects);
    }
    bool isQueryReady(QueryId id) override { return inner_.isQueryReady(id); }
    QueryAnswer takeAnswer(QueryId id) override { return inner_.takeAnswer(id); }
    const DeviceCounters& counters() const override { return inner_.counters(); }
    void resetCounters() override { inner_.resetCounters(); }

  private:
    RenderDevice& inner_;
    uint32_t dropped_;
};

class DroppingCuller final : public Culler {
  public:
    explicit DroppingCuller(uint32_t dropped) : dropped_(dropped) {}
    void reset(const BspTree& tree) override { inner_->reset(tree); }
    void cullAndRender(const BspTree& tree, const CullFrame& frame, RenderDevice& device) override {
        DroppingDevice dropping(device, dropped_);
        inner_->cullAndRender(tree, frame, dropping);
    }

  private:
    uint32_t dropped_;
    std::unique_ptr<Culler> inner_ = makeCuller(*findCuller("vfc"), CullerOptions{});
};

TEST(ErrorMetric, ACullerThatDropsAVisibleObjectShowsErrorAndTheMissAndItsPopping) {
    // Object 433: one of the four large boxes in front of the grid, in view from frame 0, with
    // grid boxes behind it.
    BenchOptions options;
    options.make_culler = [](const CullerRow&, const CullerOptions&) {
        return std::unique_ptr<Culler>(new DroppingCuller(433));
    };
    options.keep_worst_error_frame = true;
    const BenchResult result = testing::errorBench(testing::kSharedFaces, {"vfc"}, 8, options);
    const RunSummary& s = result.runs[0].summary;
    EXPECT_GT(s.error_pixels_total, 0);
    EXPECT_EQ(s.missed_objects_total, 8) << "missed on every one of the 8 frames";
    EXPECT_EQ(s.popping_events, 1u);
    EXPECT_EQ(s.popping_max_frames, 8u);
    // The worst frame's picture marks errors apart from ties.
    ASSERT_EQ(result.worst_error_frames.size(), 1u);
    const ErrorFrame& worst = result.worst_error_frames[0];
    const uint32_t w = result.metadata.width, h = result.metadata.height;
    const std::vector<uint8_t> picture = composeErrorPicture(worst, w, h);
    int64_t magenta = 0, yellow = 0;
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const uint8_t* p = picture.data() + (size_t{y} * 3 * w + 2 * w + x) * 4;
            magenta +=
                p[0] == kErrorColour[0] && p[1] == kErrorColour[1] && p[2] == kErrorColour[2];
            yellow += p[0] == kTieColour[0] && p[1] == kTieColour[1] && p[2] == kTieColour[2];
        }
    }
    EXPECT_EQ(magenta, worst.error_pixels);
    EXPECT_EQ(yellow, worst.tie_pixels);
}
}  // namespace
}  // namespace occsim
