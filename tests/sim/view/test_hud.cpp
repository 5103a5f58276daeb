// The viewer's text panel (sim/view/hud.h): the algorithm, the frame's figures and error only when
// on, every row within a 400-pixel-tall window.
#include <gtest/gtest.h>

#include "sim/view/hud.h"
#include "sim/view/node_boxes.h"

namespace occsim {
namespace {

TEST(ViewHud, ShowsTheAlgorithmAndTheFrameFiguresAndErrorOnlyWhenOn) {
    HudState s;
    s.algorithm = "chc++";
    s.algorithm_place = 5;
    s.algorithm_count = 7;
    s.frame = 12;
    s.time_s = 0.4;
    s.has_stats = true;
    s.stats.frame_ms = 12.346;
    s.stats.queries = 175;
    s.stats.triangles = 1054541;
    s.stats.error_pixels = 1234;
    s.stats.tie_pixels = 56;
    s.stats.missed_objects = 2;
    std::vector<std::string> lines = hudLines(s);
    ASSERT_GE(lines.size(), 2u);
    EXPECT_EQ(lines[0], "chc++ (5/7)   frame 12  0.40 s   path");
    EXPECT_EQ(lines[1], "frame time 12.35 ms   queries 175   triangles 1,054,541   error off (g)");
    s.error_on = true;
    s.flying = true;
    s.fly_speed_mps = 3.0;
    s.recording = true;
    s.recorded_frames = 9;
    lines = hudLines(s);
    EXPECT_EQ(lines[0], "chc++ (5/7)   frame 12  0.40 s   flying 3.0 m/s   rec 9 frames");
    EXPECT_EQ(lines[1],
              "frame time 12.35 ms   queries 175   triangles 1,054,541   error px 1,234   ties 56  "
              " missed 2");
}

// Every row of the panel, keys and legend included, lies inside the picture and apart from the
// others, in a 400-pixel-tall window wide enough for the large font and in narrower ones.
TEST(ViewHud, EveryRowFitsA400PixelTallWindow) {
    HudState s;
    s.algorithm = "statistical+";
    s.has_stats = true;
    s.message = "screenshot written: out/x.png";
    s.help = true;
    s.legend = true;
    const size_t rows = hudLines(s).size() + shownNodeBoxClasses().size();
    for (const auto& [w, h] : {std::pair{1200u, 400u}, std::pair{1000u, 400u},
                               std::pair{800u, 400u}, std::pair{1600u, 300u}}) {
        const HudLayout layout = layoutHud(w, h, s);
        ASSERT_EQ(layout.rows.size(), rows);
        const int text_h = RasterCanvas::textHeight(layout.scale);
        for (size_t i = 0; i < layout.rows.size(); ++i) {
            const HudRow& r = layout.rows[i];
            EXPECT_GE(r.y, 0) << w << "x" << h << " row " << i;
            EXPECT_LE(r.y + text_h, static_cast<int>(h)) << w << "x" << h << " row " << i;
            EXPECT_GE(r.x, 0) << w << "x" << h << " row " << i;
            EXPECT_LE(r.x + r.width, static_cast<int>(w)) << w << "x" << h << " row " << i;
            for (size_t j = 0; j < i; ++j) {
                const HudRow& o = layout.rows[j];
                const bool apart = r.x >= o.x + o.width || o.x >= r.x + r.width ||
                                   r.y >= o.y + text_h || o.y >= r.y + text_h;
                EXPECT_TRUE(apart) << w << "x" << h << " rows " << j << " and " << i;
            }
        }
        EXPECT_LE(layout.panel_height, static_cast<int>(h));
    }
}

}  // namespace
}  // namespace occsim
