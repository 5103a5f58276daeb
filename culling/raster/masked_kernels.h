// The inner kernels of the masked depth buffer (masked_depth_buffer.h), each twice: plain C++ and
// AVX2 intrinsics. Both do the same IEEE operations in the same order (no fused multiply-add), so
// they give the same results bit for bit; the tests run both. Internal to culling/raster.
#pragma once

#include <cstdint>

namespace occsim::masked_kernels {

// A triangle's three edges in buffer pixels: sample (X, Y) is covered when
// a·X + b·Y + c > margin for each edge, or = margin on an inclusive edge (the tie rule of edges
// shared without margin: of two triangles with exactly opposite edge functions, the one with
// a > 0, or a = 0 and b > 0, takes the samples on the line); x_lo..x_hi: the columns its
// bounding box spans.
struct Edges {
    double a[3], b[3], c[3], margin[3];
    bool inclusive[3];
    int32_t x_lo, x_hi;
};

// For the 8 rows row0 .. row0 + 7: the covered columns xl[r] .. xr[r] (empty when xl > xr; rows
// outside y_lo .. y_hi are empty).
void spansPlain(const Edges& e, int32_t row0, int32_t y_lo, int32_t y_hi, int32_t* xl, int32_t* xr);
void spansAvx2(const Edges& e, int32_t row0, int32_t y_lo, int32_t y_hi, int32_t* xl, int32_t* xr);

// The 8 rows' 32-bit masks of the tile whose first column is col0.
void coveragePlain(const int32_t* xl, const int32_t* xr, int32_t col0, uint32_t* out);
void coverageAvx2(const int32_t* xl, const int32_t* xr, int32_t col0, uint32_t* out);

// Whether this build and this CPU run the AVX2 kernels.
bool avx2Available();

}  // namespace occsim::masked_kernels
