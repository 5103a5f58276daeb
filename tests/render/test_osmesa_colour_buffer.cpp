// OSMesa's colour buffer outlives every context that rendered into it.
#include <gtest/gtest.h>
#if OCCSIM_HAVE_OSMESA
// GL/osmesa.h brings GL/gl.h, which cannot stand beside the core-profile header the renderer
// uses: the two OSMesa calls the test needs, as osmesa.h declares them (an OSMesaContext is a
// pointer, a GLboolean an unsigned char).
extern "C" {
void* OSMesaGetCurrentContext();
unsigned char OSMesaGetColorBuffer(void* context, int* width, int* height, int* format,
                                   void** buffer);
}
#endif

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "render/headless_context.h"
#include "render/osmesa_colour_buffer.h"

namespace occsim {
namespace {

// The colour buffer Mesa was given outlives the context (Mesa keeps the pointer in a global list
// and copies frames into it: render/osmesa_colour_buffer.h): after the context is gone nothing is
// current, and the buffer is still allocated, and still writable, also once a larger context took
// a larger one.
TEST(HeadlessBackends, OsmesaColourBufferOutlivesEveryContextThatUsedIt) {
#if OCCSIM_HAVE_OSMESA
    void* first = nullptr;
    {
        auto context = createHeadlessContext({Backend::OsMesa, {}}, 64, 48);
        int w = 0, h = 0, format = 0;
        ASSERT_TRUE(OSMesaGetColorBuffer(OSMesaGetCurrentContext(), &w, &h, &format, &first));
        EXPECT_EQ(w, 64);
        EXPECT_EQ(h, 48);
        EXPECT_TRUE(osmesaColourBufferIsKept(first));
    }
    EXPECT_EQ(OSMesaGetCurrentContext(), nullptr) << "unbound before it was destroyed";
    EXPECT_TRUE(osmesaColourBufferIsKept(first));
    {
        auto larger = createHeadlessContext({Backend::OsMesa, {}}, 256, 192);
        void* second = nullptr;
        int w = 0, h = 0, format = 0;
        ASSERT_TRUE(OSMesaGetColorBuffer(OSMesaGetCurrentContext(), &w, &h, &format, &second));
        EXPECT_NE(second, first) << "a larger buffer for a larger context";
        EXPECT_TRUE(osmesaColourBufferIsKept(second));
    }
    EXPECT_TRUE(osmesaColourBufferIsKept(first));
    std::fill_n(static_cast<unsigned char*>(first), 64 * 48 * 4, 0);  // what a late flush does
#else
    GTEST_SKIP() << "this build has no OSMesa";
#endif
    EXPECT_FALSE(osmesaColourBufferIsKept(this));
    EXPECT_EQ(osmesaColourBuffer(8, 8), osmesaColourBuffer(4, 4)) << "a block that fits is shared";
}

}  // namespace
}  // namespace occsim
