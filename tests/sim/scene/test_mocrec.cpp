// The reader of MOC's recorded frames (sim/scene/mocrec.h): the two real Castle frames in
// scenarios/assets/moc read with the counts of their SOURCE.md and land inside the view under the
// matrix convention the header states; a small file written here reads back what was written;
// every kind of bad input, and every truncation of a valid file, is one MocrecError line naming
// the file and the byte where the fault is.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "sim/scene/mocrec.h"

namespace occsim {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = OCCSIM_SOURCE_DIR;
const fs::path kFrame0 = kRoot / "scenarios/assets/moc/OcclusionCulling_0.mocrec";
const fs::path kFrame1 = kRoot / "scenarios/assets/moc/OcclusionCulling_1.mocrec";
const fs::path kFuzzSeed = kRoot / "tests/fuzz/regressions/mocrec/valid-small.mocrec";

static_assert(std::is_base_of_v<InputError, MocrecError>, "bad files end in exit code 2");

// One record of type 0 or 2 as the recorder writes it. The optional fields replace what the
// others imply, to write files the recorder never would.
struct Batch {
    uint8_t type = 0;
    int32_t result = 0;
    int32_t stride = 12, offset_y = 4, offset_w = 8;  // the vertex layout
    std::vector<float> floats;                        // the vertices, stride / 4 floats each
    std::vector<uint32_t> indices;
    std::optional<std::array<float, 16>> matrix;
    int32_t clip_planes = kMocClipPlanesAll, winding = 1;
    std::optional<int32_t> vertex_count, vertex_size, triangle_count, layout_stride;
    std::optional<uint8_t> has_matrix;
};

// Where each field of a written record starts.
struct Marks {
    size_t type, vertex_count, vertex_size, vertices, triangle_count, indices, has_matrix, matrix,
        clip_planes, winding, layout;
};

// Serialises a frame little-endian, field by field, remembering where each one went.
class Writer {
  public:
    std::vector<uint8_t> bytes;

    size_t size() const { return bytes.size(); }
    void u8(uint8_t v) { bytes.push_back(v); }
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) bytes.push_back(uint8_t(v >> (8 * i)));
    }
    void i32(int32_t v) { u32(uint32_t(v)); }
    void f32(float v) { u32(std::bit_cast<uint32_t>(v)); }

    void header(float near_clip = 0.1f, uint32_t width = 1920, uint32_t height = 1080,
                uint32_t magic = kMocrecMagic) {
        u32(magic);
        f32(near_clip);
        u32(width);
        u32(height);
    }
    Marks batch(const Batch& b) {
        Marks m{};
        m.type = size();
        u8(b.type);
        i32(b.result);
        m.vertex_count = size();
        const int32_t count =
            b.vertex_count.value_or(int32_t(b.floats.size() * 4 / size_t(b.stride)));
        i32(count);
        if (count == 0 && !b.vertex_size) return m;
        m.vertex_size = size();
        i32(b.vertex_size.value_or(b.stride));
        m.vertices = size();
        for (float f : b.floats) f32(f);
        m.triangle_count = size();
        i32(b.triangle_count.value_or(int32_t(b.indices.size() / 3)));
        m.indices = size();
        for (uint32_t i : b.indices) u32(i);
        m.has_matrix = size();
        u8(b.has_matrix.value_or(b.matrix ? 1 : 0));
        m.matrix = size();
        if (b.matrix) {
            for (float f : *b.matrix) f32(f);
        }
        m.clip_planes = size();
        i32(b.clip_planes);
        m.winding = size();
        i32(b.winding);
        m.layout = size();
        i32(b.layout_stride.value_or(b.stride));
        i32(b.offset_y);
        i32(b.offset_w);
        return m;
    }
    void rect(int32_t result, std::array<float, 5> xyxyw) {
        u8(1);
        i32(result);
        for (float f : xyxyw) f32(f);
    }
    void clear() { u8(3); }
    void end() { u8(0x7F); }
};

// clip = M * (x, y, z, 1) with the translation (0.5, 0, 0.25, 2) in elements 12 to 15 and w taking
// z from element 11: clip = (x + 0.5, y, z + 0.25, z + 2). Read transposed, it would differ.
constexpr std::array<float, 16> kMatrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0.5f, 0, 0.25f, 2};

// A quad of two triangles through kMatrix (3-float vertices, as the Castle frames have).
Batch quad() {
    Batch b;
    b.floats = {-1, -1, 1, 1, -1, 1, 1, 1, 3, -1, 1, 3};
    b.indices = {0, 1, 2, 0, 2, 3};
    b.matrix = kMatrix;
    return b;
}

// A triangle test without a matrix: clip-space (x, y, w) in a 16-byte vertex, w at offset 12 and
// a 4-byte attribute at offset 8 that MOC skips.
Batch clipTriangle() {
    Batch b;
    b.type = 2;
    b.result = 1;
    b.stride = 16;
    b.offset_w = 12;
    b.floats = {0, 0, 99, 1, 1, 0, 99, 2, 0, 1, 99, 4};
    b.indices = {0, 1, 2};
    b.winding = 0;
    b.clip_planes = 1;
    return b;
}

// The fuzz target's seed (tests/fuzz/regressions/mocrec/valid-small.mocrec) is this file: every
// record type, a clear dropping the quad before it, then a quad, a rect test and a triangle test.
std::vector<uint8_t> smallValidFile() {
    Writer w;
    w.header();
    w.batch(quad());
    w.clear();
    w.batch(quad());
    w.rect(3, {-0.5f, -0.25f, 0.5f, 0.75f, 1.5f});
    w.batch(clipTriangle());
    w.end();
    return w.bytes;
}

// A file of the header, one record and the end marker.
std::vector<uint8_t> withBatch(const Batch& b) {
    Writer w;
    w.header();
    w.batch(b);
    w.end();
    return w.bytes;
}

// Where the fields of `b` start in withBatch(b).
Marks marksOf(const Batch& b) {
    Writer w;
    w.header();
    return w.batch(b);
}

std::vector<uint8_t> bytesOf(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the MocrecError the bytes give ("" and a failure when they are accepted).
std::string errorOf(const std::vector<uint8_t>& bytes, const std::string& name = "bad.mocrec") {
    try {
        parseMocrec(bytes, name);
    } catch (const MocrecError& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted";
    return "";
}

std::string at(size_t offset) { return "bad.mocrec: byte " + std::to_string(offset) + ": "; }

// --- the real frames ---------------------------------------------------------------------------

void expectCastleBatches(const MocFrame& f) {
    EXPECT_EQ(f.width, 1920u);
    EXPECT_EQ(f.height, 1080u);
    EXPECT_FLOAT_EQ(f.near_clip, 0.1f);
    EXPECT_TRUE(f.rect_tests.empty());
    EXPECT_TRUE(f.triangle_tests.empty());
    EXPECT_EQ(f.clears, 0u);
    for (const MocBatch& b : f.occluders) {
        EXPECT_TRUE(b.had_matrix);
        EXPECT_EQ(b.clip_planes, kMocClipPlanesAll);
        EXPECT_EQ(b.backface_winding, MocWinding::Clockwise);
        EXPECT_EQ(b.result, MocResult::Visible);
        for (uint32_t i : b.indices) ASSERT_LT(i, b.clip.size());
    }
}

TEST(Mocrec, RealFramesHaveTheirRecordedCounts) {
    const MocFrame f0 = readMocrec(kFrame0);
    expectCastleBatches(f0);
    EXPECT_EQ(f0.occluders.size(), 9u);
    EXPECT_EQ(f0.triangles(), 14894u);
    EXPECT_EQ(f0.occluders.front().offset, 16u);  // right after the header

    const MocFrame f1 = readMocrec(kFrame1);
    expectCastleBatches(f1);
    EXPECT_EQ(f1.occluders.size(), 11u);
    EXPECT_EQ(f1.triangles(), 25400u);
}

// The matrix convention of mocrec.h, shown by the data: with the translation in elements 12 to 15
// nearly every vertex is in front of the camera with Direct3D's depth range (0 <= z <= w), most
// project inside the 1920 x 1080 view, and together they reach its left, right and bottom edges.
// The transposed reading would put only 59 % and 68 % in front and 4 % and 14 % in the depth range.
TEST(Mocrec, RealFramesLandInsideTheViewUnderTheStatedMatrixConvention) {
    for (const fs::path& file : {kFrame0, kFrame1}) {
        SCOPED_TRACE(file.filename().string());
        const MocFrame f = readMocrec(file);
        size_t vertices = 0, in_front = 0, depth_range = 0, inside = 0;
        glm::dvec2 lo(1.0), hi(-1.0);
        for (const MocBatch& b : f.occluders) {
            for (const glm::dvec4& c : b.clip) {
                ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) &&
                            std::isfinite(c.w));
                ++vertices;
                if (c.w <= 0.0) continue;
                ++in_front;
                if (c.z >= 0.0 && c.z <= c.w) ++depth_range;
                const glm::dvec2 ndc(c.x / c.w, c.y / c.w);
                if (std::abs(ndc.x) <= 1.0 && std::abs(ndc.y) <= 1.0) {
                    ++inside;
                    lo = glm::min(lo, ndc);
                    hi = glm::max(hi, ndc);
                }
            }
        }
        ASSERT_GT(vertices, 0u);
        EXPECT_GT(double(in_front) / double(vertices), 0.9);
        EXPECT_GT(double(depth_range) / double(vertices), 0.9);
        EXPECT_GT(double(inside) / double(vertices), 0.5);
        EXPECT_LT(lo.x, -0.95);
        EXPECT_GT(hi.x, 0.95);
        EXPECT_LT(lo.y, -0.95);
    }
}

// --- a file written here -----------------------------------------------------------------------

TEST(Mocrec, HandBuiltFileReadsBackWhatWasWritten) {
    const MocFrame f = parseMocrec(smallValidFile(), "small.mocrec");
    EXPECT_FLOAT_EQ(f.near_clip, 0.1f);
    EXPECT_EQ(f.clears, 1u);
    ASSERT_EQ(f.occluders.size(), 1u) << "the clear drops the quad before it";
    const MocBatch& q = f.occluders[0];
    EXPECT_EQ(q.offset, 16u + 174u + 1u);  // header, the dropped quad, the clear
    EXPECT_TRUE(q.had_matrix);
    EXPECT_EQ(q.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(f.triangles(), 2u);
    EXPECT_EQ(q.clip_planes, kMocClipPlanesAll);
    EXPECT_EQ(q.backface_winding, MocWinding::Clockwise);
    EXPECT_EQ(q.result, MocResult::Visible);
    const std::vector<glm::dvec4> expected{
        {-0.5, -1, 1.25, 3}, {1.5, -1, 1.25, 3}, {1.5, 1, 3.25, 5}, {-0.5, 1, 3.25, 5}};
    EXPECT_EQ(q.clip, expected);

    ASSERT_EQ(f.rect_tests.size(), 1u);
    const MocRectTest& r = f.rect_tests[0];
    EXPECT_EQ(r.result, MocResult::ViewCulled);
    EXPECT_EQ(r.x_lo, -0.5f);
    EXPECT_EQ(r.y_lo, -0.25f);
    EXPECT_EQ(r.x_hi, 0.5f);
    EXPECT_EQ(r.y_hi, 0.75f);
    EXPECT_EQ(r.w_min, 1.5f);
    EXPECT_EQ(r.occluders_before, 1u);

    ASSERT_EQ(f.triangle_tests.size(), 1u);
    const MocBatch& t = f.triangle_tests[0].batch;
    EXPECT_EQ(f.triangle_tests[0].occluders_before, 1u);
    EXPECT_EQ(t.result, MocResult::Occluded);
    EXPECT_FALSE(t.had_matrix);
    EXPECT_EQ(t.backface_winding, MocWinding::None);
    EXPECT_EQ(t.clip_planes, 1);
    // No matrix: (x, y, w) from offsets 0, 4 and 12; the attribute at 8 is not read; z = 0.
    EXPECT_EQ(t.clip, (std::vector<glm::dvec4>{{0, 0, 0, 1}, {1, 0, 0, 2}, {0, 1, 0, 4}}));
}

TEST(Mocrec, TheFuzzSeedIsTheSmallValidFile) { EXPECT_EQ(bytesOf(kFuzzSeed), smallValidFile()); }

TEST(Mocrec, RecordWithoutVerticesIsABatchWithoutTriangles) {
    Batch empty;
    const std::vector<uint8_t> bytes = withBatch(empty);
    EXPECT_EQ(bytes.size(), 16u + 9u + 1u);  // type, result, vertex count: nothing more
    const MocFrame f = parseMocrec(bytes, "empty.mocrec");
    ASSERT_EQ(f.occluders.size(), 1u);
    EXPECT_TRUE(f.occluders[0].clip.empty());
    EXPECT_EQ(f.triangles(), 0u);
}

TEST(Mocrec, ReadsAFileFromDiskAndNamesOneItCannotOpen) {
    const fs::path file = fs::temp_directory_path() / "occsim-test-mocrec-small.mocrec";
    const std::vector<uint8_t> bytes = smallValidFile();
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    EXPECT_EQ(readMocrec(file).triangles(), 2u);
    fs::remove(file);
    try {
        readMocrec(file);
        ADD_FAILURE() << "a missing file was read";
    } catch (const MocrecError& e) {
        EXPECT_EQ(std::string(e.what()),
                  file.string() + ": cannot open the file: " + "No such file or directory");
    }
    EXPECT_THROW(readMocrec(fs::temp_directory_path()), MocrecError);
}

// --- bad input ---------------------------------------------------------------------------------

TEST(Mocrec, WrongMagicNamesTheFileTheByteAndBothNumbers) {
    Writer w;
    w.header(0.1f, 1920, 1080, 0x12345678);
    w.end();
    EXPECT_EQ(errorOf(w.bytes, "file.mocrec"),
              "file.mocrec: byte 0: expected the magic number 0xA701B600, found 0x12345678");
}

TEST(Mocrec, BadHeaderValuesNameTheirByte) {
    Writer nan_near;
    nan_near.header(std::numeric_limits<float>::quiet_NaN());
    nan_near.end();
    EXPECT_EQ(errorOf(nan_near.bytes),
              at(4) + "expected a finite near clip plane of 0 or more, found NaN");
    Writer no_width;
    no_width.header(0.1f, 0, 1080);
    no_width.end();
    EXPECT_EQ(errorOf(no_width.bytes), at(8) + "expected a width from 1 to 32768 pixels, found 0");
    Writer huge_height;
    huge_height.header(0.1f, 1920, 0xFFFFFFFF);
    huge_height.end();
    EXPECT_EQ(errorOf(huge_height.bytes),
              at(12) + "expected a height from 1 to 32768 pixels, found 4294967295");
}

// The 179-byte file asked for 32768 × 32768 and ended in std::bad_alloc; the replay's
// memory budget (kMocrecMaxPixels) is refused at the width's byte, the budget's edge accepted.
TEST(Mocrec, AResolutionPastTheReplaysMemoryBudgetIsRefusedAtTheWidth) {
    const auto header = [](uint32_t width, uint32_t height) {
        Writer w;
        w.header(0.1f, width, height);
        w.batch(quad());
        w.end();
        return w.bytes;
    };
    EXPECT_EQ(errorOf(header(32768, 32768)),
              at(8) +
                  "expected at most 33554432 pixels (width × height, the replay's memory "
                  "budget), found 32768 × 32768 = 1073741824");
    EXPECT_EQ(errorOf(header(32768, 1025)),
              at(8) +
                  "expected at most 33554432 pixels (width × height, the replay's memory "
                  "budget), found 32768 × 1025 = 33587200");
    EXPECT_EQ(errorOf(header(16384, 16384)).substr(0, at(8).size()), at(8));
    for (const auto& [width, height] :
         {std::pair<uint32_t, uint32_t>{8192, 4096}, {32768, 1024}, {7680, 4320}, {1, 32768}}) {
        const MocFrame f = parseMocrec(header(width, height), "edge.mocrec");
        EXPECT_EQ(f.width, width);
        EXPECT_EQ(f.height, height);
    }
}

// In withBatch(quad()) the record starts at byte 16: its vertices at 29, the triangle count at
// 77, the indices at 81, the matrix flag at 105, the matrix at 106, the clip plane mask at 170,
// the winding at 174, the layout at 178; the file is 191 bytes.
TEST(Mocrec, QuadFileHasTheOffsetsTheseTestsName) {
    const Marks m = marksOf(quad());
    EXPECT_EQ(m.vertices, 29u);
    EXPECT_EQ(m.triangle_count, 77u);
    EXPECT_EQ(m.indices, 81u);
    EXPECT_EQ(m.has_matrix, 105u);
    EXPECT_EQ(m.clip_planes, 170u);
    EXPECT_EQ(m.layout, 178u);
    EXPECT_EQ(withBatch(quad()).size(), 191u);
}

TEST(Mocrec, CountsThatTheBytesCannotHoldAreTruncatedNotAllocated) {
    Batch b = quad();
    b.vertex_count = std::numeric_limits<int32_t>::max();
    b.vertex_size = std::numeric_limits<int32_t>::max();
    EXPECT_EQ(errorOf(withBatch(b)), at(29) +
                                         "truncated: expected 4611686014132420609 more bytes for "
                                         "the 2147483647 vertices of record 0, found 162");

    Batch tris = quad();
    tris.triangle_count = 1 << 30;
    EXPECT_EQ(errorOf(withBatch(tris)), at(81) +
                                            "truncated: expected 12884901888 more bytes for the "
                                            "3221225472 indices of record 0, found 110");
}

TEST(Mocrec, NegativeCountsNameTheirByte) {
    Batch vertices = quad();
    vertices.vertex_count = -1;
    EXPECT_EQ(errorOf(withBatch(vertices)),
              at(21) + "expected the vertex count of record 0 to be 0 or more, found -1");
    Batch triangles = quad();
    triangles.triangle_count = -3;
    EXPECT_EQ(errorOf(withBatch(triangles)),
              at(77) + "expected the triangle count of record 0 to be 0 or more, found -3");
    Batch size = quad();
    size.vertex_size = 0;
    EXPECT_EQ(errorOf(withBatch(size)),
              at(25) + "expected the vertex size of record 0 to be 4 or more, found 0");
}

TEST(Mocrec, IndexPastTheVerticesNamesTheTriangleAndTheByte) {
    Batch b = quad();
    b.indices[4] = 99;  // triangle 1, its second index: 81 + 4 * 4
    EXPECT_EQ(errorOf(withBatch(b)),
              at(97) + "triangle 1 of record 0 uses vertex 99, expected an index below 4");
}

TEST(Mocrec, NonFiniteVertexOrMatrixNamesTheByte) {
    Writer w;
    w.header();
    w.batch(quad());
    Batch b = quad();
    b.floats[3 * 2 + 1] = std::numeric_limits<float>::quiet_NaN();  // y of vertex 2
    const Marks m = w.batch(b);
    w.end();
    EXPECT_EQ(errorOf(w.bytes),
              at(m.vertices + 28) + "vertex 2 of record 1 is not finite (its y is NaN)");

    Batch matrix = quad();
    (*matrix.matrix)[13] = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(errorOf(withBatch(matrix)),
              at(106 + 52) + "element 13 of the matrix of record 0 is not finite (-infinity)");

    Writer rect;
    rect.header();
    rect.rect(0, {0, 0, 1, 1, std::numeric_limits<float>::infinity()});
    rect.end();
    EXPECT_EQ(errorOf(rect.bytes),
              at(16 + 5 + 16) + "the wmin of record 0 is not finite (infinity)");
}

TEST(Mocrec, LayoutThatNeedsMoreThanItsStrideIsRefused) {
    Batch past = quad();
    past.offset_w = 12;  // z/w would be read past the 12-byte vertex
    EXPECT_EQ(errorOf(withBatch(past)),
              at(178 + 8) +
                  "the z/w offset of record 0 is 12, which needs a stride of 16 bytes or more, "
                  "found 12");
    Batch negative = quad();
    negative.offset_y = -4;
    EXPECT_EQ(errorOf(withBatch(negative)),
              at(178 + 4) + "expected the y offset of record 0 to be 0 or more, found -4");
    Batch other = quad();
    other.layout_stride = 16;
    EXPECT_EQ(errorOf(withBatch(other)),
              at(178) +
                  "expected the layout stride of record 0 to be its vertex size, 12 bytes (byte "
                  "25), found 16");
}

TEST(Mocrec, ValuesOutsideMocsEnumsAreRefused) {
    Batch result = quad();
    result.result = 2;
    EXPECT_EQ(errorOf(withBatch(result)),
              at(17) +
                  "expected a culling result of 0 (visible), 1 (occluded) or 3 (view "
                  "culled) for record 0, found 2");
    Batch winding = quad();
    winding.winding = 3;
    EXPECT_EQ(errorOf(withBatch(winding)),
              at(174) +
                  "expected a backface winding of 0 (none), 1 (clockwise) or 2 "
                  "(counter-clockwise) for record 0, found 3");
    Batch planes = quad();
    planes.clip_planes = 32;
    EXPECT_EQ(errorOf(withBatch(planes)),
              at(170) + "expected a clip plane mask from 0 to 31 for record 0, found 32");
    Batch flag = quad();
    flag.has_matrix = 2;
    flag.matrix.reset();
    EXPECT_EQ(errorOf(withBatch(flag)),
              at(105) + "expected 0 or 1 for whether record 0 has a matrix, found 2");
}

TEST(Mocrec, UnknownRecordTypeNamesItsByte) {
    Writer w;
    w.header();
    w.batch(quad());
    const size_t type_at = w.size();
    w.u8(5);
    EXPECT_EQ(errorOf(w.bytes),
              at(type_at) +
                  "unknown type 0x05 of record 1, expected 0 (render triangles), 1 "
                  "(test rect), 2 (test triangles), 3 (clear buffer) or 0x7F (end of "
                  "file)");
}

TEST(Mocrec, TheEndMarkerEndsTheFile) {
    Writer missing;
    missing.header();
    missing.batch(quad());
    EXPECT_EQ(errorOf(missing.bytes),
              at(missing.size()) +
                  "truncated: expected record 1 or the end marker 0x7F, found the end of the file");
    Writer after;
    after.header();
    after.end();
    after.clear();
    after.clear();
    EXPECT_EQ(errorOf(after.bytes), at(17) +
                                        "expected the end of the file after the end marker at "
                                        "byte 16, found 2 more bytes");
}

TEST(Mocrec, TruncatedFieldNamesWhatItCut) {
    Writer w;
    w.header();
    const Marks m = w.batch(quad());
    w.bytes.resize(m.triangle_count + 2);
    EXPECT_EQ(errorOf(w.bytes), at(m.triangle_count) +
                                    "truncated: expected 4 more bytes for the triangle count of "
                                    "record 0, found 2");
}

// Cut after any number of bytes, the small file is a MocrecError naming a byte within what is
// left, never a crash or another exception.
TEST(Mocrec, EveryTruncationOfAValidFileIsAMocrecError) {
    const std::vector<uint8_t> whole = smallValidFile();
    ASSERT_NO_THROW(parseMocrec(whole, "cut.mocrec"));
    for (size_t length = 0; length < whole.size(); ++length) {
        SCOPED_TRACE(length);
        const std::vector<uint8_t> cut(whole.begin(), whole.begin() + std::ptrdiff_t(length));
        try {
            parseMocrec(cut, "cut.mocrec");
            ADD_FAILURE() << "a truncated file was accepted";
        } catch (const MocrecError& e) {
            const std::string message = e.what();
            ASSERT_EQ(message.rfind("cut.mocrec: byte ", 0), 0u) << message;
            const size_t offset = std::stoul(message.substr(17));
            EXPECT_LE(offset, length) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

}  // namespace
}  // namespace occsim
