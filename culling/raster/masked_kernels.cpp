// The masked depth buffer's kernels: the plain path, and the AVX2 path beside it (compiled for
// AVX2 by a target attribute, called only where the CPU has it). See masked_kernels.h.
#include "culling/raster/masked_kernels.h"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define OCCSIM_MASKED_AVX2 1
#else
#define OCCSIM_MASKED_AVX2 0
#endif

namespace occsim::masked_kernels {

void spansPlain(const Edges& e, int32_t row0, int32_t y_lo, int32_t y_hi, int32_t* xl,
                int32_t* xr) {
    const double q_lo = e.x_lo - 2.0, q_hi = e.x_hi + 2.0;  // keeps every value an int32
    for (int32_t r = 0; r < 8; ++r) {
        const double y = row0 + r;
        double lo = e.x_lo, hi = e.x_hi;
        for (int i = 0; i < 3; ++i) {
            const double t = (e.margin[i] - e.b[i] * y) - e.c[i];
            if (e.a[i] > 0.0) {
                const double q = std::min(std::max(t / e.a[i], q_lo), q_hi);
                lo = std::max(lo, e.inclusive[i] ? std::ceil(q) : std::floor(q) + 1.0);
            } else if (e.a[i] < 0.0) {
                const double q = std::min(std::max(t / e.a[i], q_lo), q_hi);
                hi = std::min(hi, std::ceil(q) - 1.0);
            } else if (e.inclusive[i] ? t > 0.0 : !(0.0 > t)) {
                lo = e.x_hi + 1.0;
            }
        }
        if (row0 + r < y_lo || row0 + r > y_hi) lo = e.x_hi + 1.0;
        xl[r] = static_cast<int32_t>(lo);
        xr[r] = static_cast<int32_t>(hi);
    }
}

void coveragePlain(const int32_t* xl, const int32_t* xr, int32_t col0, uint32_t* out) {
    for (int r = 0; r < 8; ++r) {
        const int32_t l = std::max(xl[r] - col0, 0), h = std::min(xr[r] - col0, 31);
        out[r] = l > h ? 0u : (~0u >> (31 - h)) & (~0u << l);
    }
}

#if OCCSIM_MASKED_AVX2

__attribute__((target("avx2"))) void spansAvx2(const Edges& e, int32_t row0, int32_t y_lo,
                                               int32_t y_hi, int32_t* xl, int32_t* xr) {
    const __m256d q_lo = _mm256_set1_pd(e.x_lo - 2.0), q_hi = _mm256_set1_pd(e.x_hi + 2.0);
    const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
    const __m256d empty = _mm256_set1_pd(e.x_hi + 1.0);
    for (int32_t g = 0; g < 8; g += 4) {
        const __m256d y = _mm256_set_pd(row0 + g + 3, row0 + g + 2, row0 + g + 1, row0 + g);
        __m256d lo = _mm256_set1_pd(e.x_lo), hi = _mm256_set1_pd(e.x_hi);
        for (int i = 0; i < 3; ++i) {
            const __m256d t = _mm256_sub_pd(_mm256_sub_pd(_mm256_set1_pd(e.margin[i]),
                                                          _mm256_mul_pd(_mm256_set1_pd(e.b[i]), y)),
                                            _mm256_set1_pd(e.c[i]));
            if (e.a[i] != 0.0) {
                __m256d q = _mm256_div_pd(t, _mm256_set1_pd(e.a[i]));
                q = _mm256_min_pd(_mm256_max_pd(q, q_lo), q_hi);
                if (e.a[i] > 0.0) {
                    lo = _mm256_max_pd(lo, e.inclusive[i] ? _mm256_ceil_pd(q)
                                                          : _mm256_add_pd(_mm256_floor_pd(q), one));
                } else {
                    hi = _mm256_min_pd(hi, _mm256_sub_pd(_mm256_ceil_pd(q), one));
                }
            } else {
                const __m256d out = e.inclusive[i] ? _mm256_cmp_pd(t, zero, _CMP_GT_OQ)
                                                   : _mm256_cmp_pd(t, zero, _CMP_NLT_UQ);
                lo = _mm256_blendv_pd(lo, empty, out);
            }
        }
        const __m256d outside = _mm256_or_pd(_mm256_cmp_pd(y, _mm256_set1_pd(y_lo), _CMP_LT_OQ),
                                             _mm256_cmp_pd(y, _mm256_set1_pd(y_hi), _CMP_GT_OQ));
        lo = _mm256_blendv_pd(lo, empty, outside);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(xl + g), _mm256_cvtpd_epi32(lo));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(xr + g), _mm256_cvtpd_epi32(hi));
    }
}

__attribute__((target("avx2"))) void coverageAvx2(const int32_t* xl, const int32_t* xr,
                                                  int32_t col0, uint32_t* out) {
    const __m256i base = _mm256_set1_epi32(col0);
    const __m256i l = _mm256_max_epi32(
        _mm256_sub_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(xl)), base),
        _mm256_setzero_si256());
    const __m256i h = _mm256_min_epi32(
        _mm256_sub_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(xr)), base),
        _mm256_set1_epi32(31));
    const __m256i ones = _mm256_set1_epi32(-1);
    // Shift counts past 31 give 0 (AVX2), which is what an empty row needs anyway.
    const __m256i mask =
        _mm256_and_si256(_mm256_srlv_epi32(ones, _mm256_sub_epi32(_mm256_set1_epi32(31), h)),
                         _mm256_sllv_epi32(ones, l));
    const __m256i empty = _mm256_cmpgt_epi32(l, h);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_andnot_si256(empty, mask));
}

bool avx2Available() { return __builtin_cpu_supports("avx2"); }

#else

void spansAvx2(const Edges& e, int32_t row0, int32_t y_lo, int32_t y_hi, int32_t* xl, int32_t* xr) {
    spansPlain(e, row0, y_lo, y_hi, xl, xr);
}
void coverageAvx2(const int32_t* xl, const int32_t* xr, int32_t col0, uint32_t* out) {
    coveragePlain(xl, xr, col0, out);
}
bool avx2Available() { return false; }

#endif

}  // namespace occsim::masked_kernels
