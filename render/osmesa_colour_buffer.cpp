#include "render/osmesa_colour_buffer.h"

#include <cstddef>
#include <memory>
#include <mutex>
#include <vector>

namespace occsim {
namespace {

struct Block {
    std::unique_ptr<unsigned char[]> bytes;
    size_t size = 0;
};

struct Blocks {
    std::mutex mutex;
    std::vector<Block> all;  // the last one is the largest
};

// Never destroyed: a static object would be freed at exit, before Mesa's own clean-up may flush.
Blocks& blocks() {
    static Blocks* const kept = new Blocks;
    return *kept;
}

}  // namespace

unsigned char* osmesaColourBuffer(uint32_t width, uint32_t height) {
    const size_t size = size_t{width} * height * 4;
    Blocks& b = blocks();
    const std::lock_guard<std::mutex> lock(b.mutex);
    if (b.all.empty() || b.all.back().size < size) {
        b.all.push_back({std::make_unique<unsigned char[]>(size), size});
    }
    return b.all.back().bytes.get();
}

bool osmesaColourBufferIsKept(const void* p) {
    Blocks& b = blocks();
    const std::lock_guard<std::mutex> lock(b.mutex);
    const auto* byte = static_cast<const unsigned char*>(p);
    for (const Block& block : b.all) {
        if (byte >= block.bytes.get() && byte < block.bytes.get() + block.size) return true;
    }
    return false;
}

}  // namespace occsim
