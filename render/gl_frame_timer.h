// GPU time of a frame: a GL_TIME_ELAPSED timer query around the culled render. The result is
// read after glFinish, so fetching it never waits. Only meaningful on a real GPU: software
// rasterisers (llvmpipe) do not time rasterisation with it (ContextInfo::gpu_time_meaningful).
#pragma once

#include <cstdint>

namespace occsim {

class GlFrameTimer {
  public:
    GlFrameTimer();  // needs a current context
    ~GlFrameTimer();
    GlFrameTimer(const GlFrameTimer&) = delete;
    GlFrameTimer& operator=(const GlFrameTimer&) = delete;

    void begin();
    void end();
    // The last begin()-end() span in milliseconds; call after the frame's glFinish.
    double resultMs();

  private:
    uint32_t query_ = 0;
    bool running_ = false;
};

}  // namespace occsim
