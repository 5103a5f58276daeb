// Reads .mocrec files (sim/scene/mocrec.h). A cursor over the bytes checks that each field fits in
// what remains before it reads it, and assembles every number little-endian byte by byte, so
// neither the host's byte order nor the alignment of the buffer matters.
#include "sim/scene/mocrec.h"

#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace occsim {
namespace {

constexpr uint8_t kRenderTriangles = 0;
constexpr uint8_t kTestRect = 1;
constexpr uint8_t kTestTriangles = 2;
constexpr uint8_t kClearBuffer = 3;
constexpr uint8_t kEndOfFile = 0x7F;

std::string hex(uint32_t value, int digits) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%0*X", digits, value);
    return text;
}

// The shortest text that reads back as `value`; "NaN", "infinity" and "-infinity" for the rest.
std::string floatText(float value) {
    if (std::isnan(value)) return "NaN";
    if (std::isinf(value)) return value > 0 ? "infinity" : "-infinity";
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, value).ptr;
    return std::string(text, end);
}

class Cursor {
  public:
    Cursor(std::span<const uint8_t> bytes, const std::string& file) : bytes_(bytes), file_(file) {}

    uint64_t offset() const { return pos_; }
    uint64_t left() const { return bytes_.size() - pos_; }

    [[noreturn]] void fail(uint64_t at, const std::string& what) const {
        throw MocrecError(file_ + ": byte " + std::to_string(at) + ": " + what);
    }

    // Fails unless `size` more bytes remain for `what`; every read goes through here first.
    void need(uint64_t size, const std::string& what) const {
        if (size > left()) {
            fail(pos_, "truncated: expected " + std::to_string(size) + " more byte" +
                           (size == 1 ? "" : "s") + " for " + what + ", found " +
                           std::to_string(left()));
        }
    }
    void skip(uint64_t size, const std::string& what) {
        need(size, what);
        pos_ += size;
    }

    uint8_t u8(const std::string& what) {
        need(1, what);
        return bytes_[pos_++];
    }
    uint32_t u32(const std::string& what) {
        need(4, what);
        const uint32_t v = u32At(pos_);
        pos_ += 4;
        return v;
    }
    int32_t i32(const std::string& what) { return static_cast<int32_t>(u32(what)); }
    float f32(const std::string& what) { return std::bit_cast<float>(u32(what)); }

    // At an offset already checked by need().
    uint32_t u32At(uint64_t at) const {
        return uint32_t{bytes_[at]} | uint32_t{bytes_[at + 1]} << 8 |
               uint32_t{bytes_[at + 2]} << 16 | uint32_t{bytes_[at + 3]} << 24;
    }
    float f32At(uint64_t at) const { return std::bit_cast<float>(u32At(at)); }

  private:
    std::span<const uint8_t> bytes_;
    const std::string& file_;
    uint64_t pos_ = 0;
};

MocResult readResult(Cursor& c, const std::string& record) {
    const uint64_t at = c.offset();
    const int32_t v = c.i32("the culling result of " + record);
    if (v != 0 && v != 1 && v != 3) {
        c.fail(at,
               "expected a culling result of 0 (visible), 1 (occluded) or 3 (view culled) for " +
                   record + ", found " + std::to_string(v));
    }
    return static_cast<MocResult>(v);
}

// A count or size that must be at least `min`; the bytes it promises are checked by their reader.
int32_t readCount(Cursor& c, const std::string& what, int32_t min) {
    const uint64_t at = c.offset();
    const int32_t v = c.i32(what);
    if (v < min) {
        c.fail(at, "expected " + what + " to be " + std::to_string(min) + " or more, found " +
                       std::to_string(v));
    }
    return v;
}

// The vertex layout's offset of y or of z/w: inside the stride, with room for its float.
int32_t readLayoutOffset(Cursor& c, const std::string& what, int32_t stride) {
    const uint64_t at = c.offset();
    const int32_t v = c.i32(what);
    if (v < 0) c.fail(at, "expected " + what + " to be 0 or more, found " + std::to_string(v));
    if (int64_t{v} + 4 > stride) {
        c.fail(at, what + " is " + std::to_string(v) + ", which needs a stride of " +
                       std::to_string(int64_t{v} + 4) + " bytes or more, found " +
                       std::to_string(stride));
    }
    return v;
}

// The body of a type 0 or 2 record, after its type byte at `at`.
MocBatch readBatch(Cursor& c, uint64_t record_index, uint64_t at) {
    const std::string record = "record " + std::to_string(record_index);
    MocBatch batch;
    batch.offset = at;
    batch.result = readResult(c, record);
    const int32_t vertex_count = readCount(c, "the vertex count of " + record, 0);
    if (vertex_count == 0) return batch;  // the recorder writes nothing more
    const uint64_t size_at = c.offset();
    const int32_t vertex_size = readCount(c, "the vertex size of " + record, 4);

    const uint64_t vertices_at = c.offset();
    c.skip(uint64_t(vertex_count) * uint64_t(vertex_size),
           "the " + std::to_string(vertex_count) + " vertices of " + record);

    const int32_t triangle_count = readCount(c, "the triangle count of " + record, 0);
    const uint64_t indices_at = c.offset();
    const uint64_t index_count = uint64_t(triangle_count) * 3;
    c.need(index_count * 4, "the " + std::to_string(index_count) + " indices of " + record);
    batch.indices.resize(index_count);
    for (uint64_t i = 0; i < index_count; ++i) {
        const uint32_t v = c.u32At(indices_at + 4 * i);
        if (v >= uint32_t(vertex_count)) {
            c.fail(indices_at + 4 * i, "triangle " + std::to_string(i / 3) + " of " + record +
                                           " uses vertex " + std::to_string(v) +
                                           ", expected an index below " +
                                           std::to_string(vertex_count));
        }
        batch.indices[i] = v;
    }
    c.skip(index_count * 4, "the indices of " + record);

    const uint64_t flag_at = c.offset();
    const uint8_t has_matrix = c.u8("the matrix flag of " + record);
    if (has_matrix > 1) {
        c.fail(flag_at, "expected 0 or 1 for whether " + record + " has a matrix, found " +
                            std::to_string(has_matrix));
    }
    std::array<double, 16> m{};
    if (has_matrix) {
        const uint64_t matrix_at = c.offset();
        c.skip(64, "the matrix of " + record);
        for (uint64_t k = 0; k < 16; ++k) {
            const float e = c.f32At(matrix_at + 4 * k);
            if (!std::isfinite(e)) {
                c.fail(matrix_at + 4 * k, "element " + std::to_string(k) + " of the matrix of " +
                                              record + " is not finite (" + floatText(e) + ")");
            }
            m[k] = e;
        }
    }
    batch.had_matrix = has_matrix == 1;

    const uint64_t mask_at = c.offset();
    batch.clip_planes = c.i32("the clip plane mask of " + record);
    if (batch.clip_planes < 0 || batch.clip_planes > kMocClipPlanesAll) {
        c.fail(mask_at, "expected a clip plane mask from 0 to 31 for " + record + ", found " +
                            std::to_string(batch.clip_planes));
    }
    const uint64_t winding_at = c.offset();
    const int32_t winding = c.i32("the backface winding of " + record);
    if (winding < 0 || winding > 2) {
        c.fail(winding_at,
               "expected a backface winding of 0 (none), 1 (clockwise) or 2 (counter-clockwise) "
               "for " +
                   record + ", found " + std::to_string(winding));
    }
    batch.backface_winding = static_cast<MocWinding>(winding);

    c.need(12, "the vertex layout of " + record);
    const uint64_t stride_at = c.offset();
    const int32_t stride = c.i32("the vertex layout of " + record);
    if (stride != vertex_size) {
        c.fail(stride_at, "expected the layout stride of " + record + " to be its vertex size, " +
                              std::to_string(vertex_size) + " bytes (byte " +
                              std::to_string(size_at) + "), found " + std::to_string(stride));
    }
    const int32_t offset_y = readLayoutOffset(c, "the y offset of " + record, stride);
    const int32_t offset_w = readLayoutOffset(c, "the z/w offset of " + record, stride);

    // Now that the layout is known, the vertices read earlier can be decoded.
    batch.clip.resize(uint32_t(vertex_count));
    for (uint32_t v = 0; v < uint32_t(vertex_count); ++v) {
        const uint64_t base = vertices_at + uint64_t(v) * uint64_t(stride);
        const std::array<uint64_t, 3> at_of{base, base + uint64_t(offset_y),
                                            base + uint64_t(offset_w)};
        std::array<double, 3> p{};
        for (int k = 0; k < 3; ++k) {
            const float f = c.f32At(at_of[k]);
            if (!std::isfinite(f)) {
                const char* name = k == 0 ? "x" : k == 1 ? "y" : has_matrix ? "z" : "w";
                c.fail(at_of[k], "vertex " + std::to_string(v) + " of " + record +
                                     " is not finite (its " + name + " is " + floatText(f) + ")");
            }
            p[k] = f;
        }
        if (has_matrix) {
            glm::dvec4 out;
            for (int r = 0; r < 4; ++r) {
                out[r] = p[0] * m[r] + p[1] * m[4 + r] + p[2] * m[8 + r] + m[12 + r];
            }
            batch.clip[v] = out;
        } else {
            batch.clip[v] = glm::dvec4(p[0], p[1], 0.0, p[2]);
        }
    }
    return batch;
}

MocRectTest readRect(Cursor& c, uint64_t record_index, uint64_t at) {
    const std::string record = "record " + std::to_string(record_index);
    MocRectTest rect;
    rect.offset = at;
    rect.result = readResult(c, record);
    const uint64_t floats_at = c.offset();
    c.skip(20, "the rectangle of " + record);
    static constexpr std::array<const char*, 5> kNames{"xmin", "ymin", "xmax", "ymax", "wmin"};
    std::array<float, 5> v{};
    for (uint64_t k = 0; k < 5; ++k) {
        v[k] = c.f32At(floats_at + 4 * k);
        if (!std::isfinite(v[k])) {
            c.fail(floats_at + 4 * k, std::string("the ") + kNames[k] + " of " + record +
                                          " is not finite (" + floatText(v[k]) + ")");
        }
    }
    rect.x_lo = v[0];
    rect.y_lo = v[1];
    rect.x_hi = v[2];
    rect.y_hi = v[3];
    rect.w_min = v[4];
    return rect;
}

}  // namespace

uint64_t MocFrame::triangles() const {
    uint64_t total = 0;
    for (const MocBatch& b : occluders) total += b.triangles();
    return total;
}

MocFrame parseMocrec(std::span<const uint8_t> bytes, const std::string& file_name) {
    Cursor c(bytes, file_name);
    MocFrame frame;
    const uint32_t magic = c.u32("the magic number " + hex(kMocrecMagic, 8));
    if (magic != kMocrecMagic) {
        c.fail(0, "expected the magic number " + hex(kMocrecMagic, 8) + ", found " + hex(magic, 8));
    }
    const uint64_t near_at = c.offset();
    frame.near_clip = c.f32("the near clip plane");
    if (!(frame.near_clip >= 0.0f) || !std::isfinite(frame.near_clip)) {
        c.fail(near_at, "expected a finite near clip plane of 0 or more, found " +
                            floatText(frame.near_clip));
    }
    const uint64_t width_at = c.offset();
    for (uint32_t* side : {&frame.width, &frame.height}) {
        const uint64_t at = c.offset();
        const char* name = side == &frame.width ? "width" : "height";
        *side = c.u32(std::string("the ") + name);
        if (*side == 0 || *side > kMocrecMaxResolution) {
            c.fail(at, std::string("expected a ") + name + " from 1 to " +
                           std::to_string(kMocrecMaxResolution) + " pixels, found " +
                           std::to_string(*side));
        }
    }
    const uint64_t pixels = uint64_t{frame.width} * frame.height;
    if (pixels > kMocrecMaxPixels) {
        c.fail(width_at, "expected at most " + std::to_string(kMocrecMaxPixels) +
                             " pixels (width × height, the replay's memory budget), found " +
                             std::to_string(frame.width) + " × " + std::to_string(frame.height) +
                             " = " + std::to_string(pixels));
    }

    for (uint64_t record = 0;; ++record) {
        const uint64_t at = c.offset();
        if (c.left() == 0) {
            c.fail(at, "truncated: expected record " + std::to_string(record) +
                           " or the end marker 0x7F, found the end of the file");
        }
        const uint8_t type = c.u8("the type of record " + std::to_string(record));
        switch (type) {
            case kRenderTriangles:
                frame.occluders.push_back(readBatch(c, record, at));
                break;
            case kTestTriangles:
                frame.triangle_tests.push_back({readBatch(c, record, at), frame.occluders.size()});
                break;
            case kTestRect:
                frame.rect_tests.push_back(readRect(c, record, at));
                frame.rect_tests.back().occluders_before = frame.occluders.size();
                break;
            case kClearBuffer:
                frame.occluders.clear();
                frame.rect_tests.clear();
                frame.triangle_tests.clear();
                ++frame.clears;
                break;
            case kEndOfFile:
                if (c.left() != 0) {
                    c.fail(c.offset(),
                           "expected the end of the file after the end marker at byte " +
                               std::to_string(at) + ", found " + std::to_string(c.left()) +
                               " more bytes");
                }
                return frame;
            default:
                c.fail(at, "unknown type " + hex(type, 2) + " of record " + std::to_string(record) +
                               ", expected 0 (render triangles), 1 (test rect), 2 (test "
                               "triangles), 3 (clear buffer) or 0x7F (end of file)");
        }
    }
}

MocFrame readMocrec(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec)) {
        throw MocrecError(name + ": cannot open the file: it is a directory");
    }
    struct Closer {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    // stdio rather than ifstream: fopen sets errno, so the message can say why it failed.
    const std::unique_ptr<std::FILE, Closer> stream(std::fopen(name.c_str(), "rb"));
    if (!stream) throw MocrecError(name + ": cannot open the file: " + std::strerror(errno));
    std::vector<uint8_t> bytes;
    uint8_t buffer[1 << 16];
    size_t read = 0;
    while ((read = std::fread(buffer, 1, sizeof buffer, stream.get())) > 0) {
        bytes.insert(bytes.end(), buffer, buffer + read);
    }
    if (std::ferror(stream.get())) {
        throw MocrecError(name + ": cannot read the file: " + std::strerror(errno));
    }
    return parseMocrec(bytes, name);
}

}  // namespace occsim
