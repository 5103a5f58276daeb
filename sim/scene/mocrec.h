// Intel Masked Occlusion Culling's recorded frames (.mocrec, written by its FrameRecorder; the
// format is in scenarios/assets/moc/SOURCE.md) read into plain data: every occluder batch a frame
// rendered into MOC, in clip space, and the queries it asked. Nothing of MOC's code is used.
//
// Conventions of the result:
//  - Clip space is MOC's, which follows Direct3D (its default): a point is inside the view where
//    -w <= x <= w, -w <= y <= w and 0 <= z <= w; w is the view depth. MOC itself never reads z
//    (it rasterises 1/w as depth), so depth is best taken from w.
//  - The recorded model-to-clip matrix is 16 floats of which element 4 * c + r is row r, column c
//    of M in clip = M * (x, y, z, 1): column-major for post-multiplication (OpenGL), which are the
//    same 16 floats as row-major for Direct3D's pre-multiplication clip = (x, y, z, 1) * M; the
//    translation is in elements 12 to 15. MOC's header names both (they are one layout) and its
//    transform reads the floats so; the data agrees. Read so, 94 % and 100 % of the vertices of
//    the two recorded Castle frames have w > 0 and 0 <= z <= w (z / w falls with distance: the
//    sample's depth is reversed), 61 % and 93 % project inside the view, and the projected vertices
//    reach its left, right and bottom edges (frame 1 has sky at the top). Read transposed
//    (translation in elements 3, 7, 11, 15), only 59 % and 68 % would have w > 0 and 4 % and 14 %
//    would have 0 <= z <= w.
//  - A vertex is the three floats at byte offsets 0, y and z/w of the record's vertex layout. With
//    a matrix they are the model-space (x, y, z), w = 1, and clip = M * (x, y, z, 1), in double.
//    Without one they are already MOC's clip-space (x, y, w); the file holds no z, so clip.z = 0.
//  - Records are numbered from 0 in file order, every type counted; a record's triangles and
//    vertices from 0 within it. Indices are relative to the record's first vertex, as recorded.
//  - A "clear buffer" record (type 3) drops every occluder batch before it, and the tests before
//    it too: they were answered against the buffer it cleared, so the frame is what follows the
//    last clear. A record with no vertices (nothing else follows its vertex count in the file) is
//    kept as a batch without triangles; its clip plane mask and winding are 0.
//
// What can fail: any input that is not such a file throws MocrecError with one line,
// "<file>: byte <offset>: <what was expected>", the offset being where the offending field
// starts (for a file that ends too early, the field it cuts). Every count and size is checked
// against the bytes that remain before anything is allocated, so a broken file is an error, never
// a huge allocation (at most 8 bytes of result per byte of file) or a read past the end. Values
// are checked too: a header outside its ranges below, a result, winding or clip plane mask outside
// MOC's enums, a "has matrix" byte other than 0 or 1, a vertex layout whose offsets need more than
// its stride (or whose stride is not the record's vertex size), a non-finite vertex coordinate,
// matrix element or rectangle, an index not below the record's vertex count, an unknown record
// type, bytes after the end marker 0x7F or no end marker.
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

#include "sim/scenario/errors.h"

namespace occsim {

inline constexpr uint32_t kMocrecMagic = 0xA701B600;
// A width or height beyond this is no view MOC buffered but a number from a broken file.
inline constexpr uint32_t kMocrecMaxResolution = 32768;
// `masked-replay` holds about 26 bytes a pixel (the exact buffer's depth, each layout's bounds
// and buffer, the picture): a frame of more pixels than this is refused before anything is
// allocated (docs/masked.md: 0.87 GB resident for an empty 8192 × 4096 frame; an 8K frame,
// 7680 × 4320, fits; 16384 × 16384 took 6.4 GB).
inline constexpr uint64_t kMocrecMaxPixels = uint64_t{1} << 25;

// MOC's enums, as recorded.
enum class MocResult : int32_t { Visible = 0, Occluded = 1, ViewCulled = 3 };
enum class MocWinding : int32_t { None = 0, Clockwise = 1, CounterClockwise = 2 };
inline constexpr int32_t kMocClipPlanesAll = 0x1F;  // near 1, left 2, right 4, bottom 8, top 16

// One "render triangles" (type 0) or "test triangles" (type 2) record.
struct MocBatch {
    std::vector<glm::dvec4> clip;   // every vertex in clip space (x, y, z, w), finite
    std::vector<uint32_t> indices;  // 3 per triangle, each < clip.size()
    int32_t clip_planes = 0;        // the record's clip plane mask, bits of kMocClipPlanesAll
    MocWinding backface_winding = MocWinding::None;  // the winding MOC culls as back-facing
    MocResult result = MocResult::Visible;           // what MOC answered when it was recorded
    bool had_matrix = false;  // clip came through the record's model-to-clip matrix
    uint64_t offset = 0;      // byte offset of the record (its type byte) in the file

    uint64_t triangles() const { return indices.size() / 3; }
};

// One "test rect" (type 1) record: a screen rectangle in NDC at the nearest depth w_min.
struct MocRectTest {
    float x_lo = 0, y_lo = 0, x_hi = 0, y_hi = 0;  // NDC, as recorded (finite; order unchecked)
    float w_min = 0;                               // clip-space w of the rectangle's nearest point
    MocResult result = MocResult::Visible;
    uint64_t occluders_before = 0;  // how many of MocFrame::occluders were rendered before it
    uint64_t offset = 0;
};

// A test triangles record with its place among the occluders, like MocRectTest's.
struct MocTriangleTest {
    MocBatch batch;
    uint64_t occluders_before = 0;
};

struct MocFrame {
    float near_clip = 0;              // MOC's near clip plane as clip-space w (finite, >= 0)
    uint32_t width = 0, height = 0;   // MOC's depth buffer in pixels, 1 to kMocrecMaxResolution,
                                      // at most kMocrecMaxPixels in all
    std::vector<MocBatch> occluders;  // type 0 records after the last clear, in file order
    std::vector<MocRectTest> rect_tests;
    std::vector<MocTriangleTest> triangle_tests;
    uint32_t clears = 0;  // clear buffer records in the file

    uint64_t triangles() const;  // over occluders
};

// Reads a whole .mocrec held in memory; `file_name` starts every message. Throws MocrecError.
MocFrame parseMocrec(std::span<const uint8_t> bytes, const std::string& file_name);
// Reads the file; one that cannot be opened or read is a MocrecError as well.
MocFrame readMocrec(const std::filesystem::path& file);

}  // namespace occsim
