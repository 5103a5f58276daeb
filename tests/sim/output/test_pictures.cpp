// Pictures taken by a run (sim/output/pictures.h): a worst window's frame per configuration with
// its validation overlay (what it missed in red, what it drew while hidden in yellow), or the
// frame alone when its verdicts are not there, and one file per configuration whose window it
// ends. The captured frames and bird's-eye pictures of real runs: test_run_outputs.cpp and
// tests/system.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "overlay_view.h"
#include "sim/output/error_picture.h"
#include "sim/output/moments.h"
#include "sim/output/pictures.h"
#include "sim/output/validation_overlay.h"

namespace occsim {
namespace {

using testing::kOverlayNear;
using testing::kOverlaySize;
using testing::overlayView;
using testing::pixelsOf;

// A grey 64 x 64 frame 1.5 s into the path; ground truth shows object 0 in the frame's bottom
// left corner; objects 0 and 1 are boxes 10 m ahead, left and right of the centre.
struct MadeUpFrame {
    std::vector<uint8_t> rgba = std::vector<uint8_t>(size_t{kOverlaySize} * kOverlaySize * 4, 90);
    std::vector<uint32_t> ids = std::vector<uint32_t>(size_t{kOverlaySize} * kOverlaySize, 0);
    std::vector<Aabb> boxes = {Aabb{{-5, -1, -11}, {-3, 1, -9}}, Aabb{{3, -1, -11}, {5, 1, -9}}};

    MadeUpFrame() {
        for (uint32_t y = 0; y < 4; ++y) {
            for (uint32_t x = 0; x < 4; ++x) ids[size_t{y} * kOverlaySize + x] = 1;
        }
    }
    ReplayedFrame replayed() const {
        return ReplayedFrame{45,  1.5,   rgba,          kOverlaySize, kOverlaySize,
                             ids, boxes, overlayView(), kOverlayNear, {}};
    }
};

TEST(WindowPicture, TheConfigurationsMissesAreRedAndItsOverDrawYellowOverTheFrame) {
    const MadeUpFrame made;
    const FrameVerdicts verdicts{{0}, {1}};
    const RasterCanvas picture =
        windowPicture(made.replayed(), WindowVerdicts{"chc", &verdicts, true});
    const uint32_t scale = errorPictureScale(kOverlaySize);
    EXPECT_GE(picture.width(), kOverlaySize * scale);
    EXPECT_GT(picture.height(), kOverlaySize * scale) << "a strip above the frame";
    EXPECT_GT(pixelsOf(picture, kMissedColour), 10u) << "object 0's box";
    EXPECT_GT(pixelsOf(picture, kDrawnHiddenColour), 10u) << "object 1's box";
    // Object 0's own pixels, bottom left, tinted red over the grey.
    const Rgb corner = picture.at(1, static_cast<int>(picture.height()) - 2);
    EXPECT_GT(corner.r, 120);
    EXPECT_LT(corner.g, 80);
}

TEST(WindowPicture, WithoutVerdictsTheFrameIsShownAlone) {
    const MadeUpFrame made;
    for (bool measured : {false, true}) {
        const RasterCanvas picture =
            windowPicture(made.replayed(), WindowVerdicts{"chc", nullptr, measured});
        EXPECT_EQ(pixelsOf(picture, kMissedColour), 0u);
        EXPECT_EQ(pixelsOf(picture, kDrawnHiddenColour), 0u);
        EXPECT_EQ(picture.at(1, static_cast<int>(picture.height()) - 2), (Rgb{90, 90, 90}));
    }
}

TEST(WindowPicture, EachConfigurationWhoseWindowItEndsGetsItsOwnFile) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("occsim-window-pictures-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const MadeUpFrame made;
    const FrameVerdicts verdicts{{0}, {}};
    ReplayedFrame frame = made.replayed();
    frame.windows = {WindowVerdicts{"chc", &verdicts, true},
                     WindowVerdicts{"statistical+", nullptr, true}};
    PictureRecorder recorder(dir, {}, std::nullopt);
    recorder.onWindowFrame(frame);
    const std::vector<std::string> expected = {windowPictureName("chc", 45),
                                               windowPictureName("statistical+", 45)};
    EXPECT_EQ(recorder.windowFiles(), expected);
    for (const std::string& name : expected) {
        EXPECT_GT(std::filesystem::file_size(dir / name), 100u) << name;
    }
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace occsim
