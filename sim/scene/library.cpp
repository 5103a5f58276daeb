// Library: the second test scene of Kovalčík & Sochor (2005), "a computer-generated library with
// shelves containing nearly 40,000 books ... The shelves does not have back sides, so the books
// were the main occluders". Here, too, a shelf is only a frame (side panels and boards), and what
// hides the next aisle is the books, with gaps above and between them to see through.
//
// Layout (metres, y up; the floor's top is y = 0). `rows` rows of shelving run along +x, one
// behind the other in +z: row r occupies z in [r * pitch, r * pitch + kShelfDepth] with
// pitch = kShelfDepth + aisle_width, and x in [0, shelves_per_row * unit_width + side], where
// unit_width = books_per_level * kBookSlot + kSideThickness. The books of every row stand with
// their spines towards +z, so each aisle shows spines on one side and page edges on the other
// (there are no back panels to hide them). Aisles of aisle_width run in front of the first row,
// between rows and behind the last row, and cross aisles of aisle_width at both ends of the rows;
// walls enclose the room.
//
// Objects, in this order: the floor, the four walls, then per row and shelf unit its side panels
// (shared between neighbouring units), its boards (levels + a top board), and the books of each
// level. Every book is its own object; books share four unit meshes (48 to 72 triangles: covers,
// page block, spine, raised bands) stretched to each book's thickness, height and depth.
//
// No two objects touch: books stand 1 mm above their board and 1.5 mm or more apart, boards stop
// 1 mm short of the side panels, and everything stands 2 mm above the floor. Where two objects
// touch, their depths are equal along the contact line, and a pixel there whose depths tie
// exactly shows whichever object was drawn first, an error no culling decision caused.
//
// Lanes: for people, 2 cm above the floor (a mover's base rests on the lane point). One loop goes
// round each row through the aisles on both sides and the cross aisles, 3/8 of the aisle width
// from the books, so the loops of neighbouring rows share no line.
#include <algorithm>
#include <stdexcept>

#include "occsim/culling/geometry/random.h"
#include "sim/scene/generators.h"
#include "sim/scene/primitives.h"

namespace occsim {
namespace {

constexpr double kShelfDepth = 0.35;      // side panels and boards, front to back
constexpr double kSideThickness = 0.025;  // side panels
constexpr double kBoardThickness = 0.025;
constexpr double kBoardInset = 0.01;   // boards stop short of the sides' front edges
constexpr double kFirstBoardY = 0.08;  // bottom of the lowest board (a kick space below)
constexpr double kLevelPitch = 0.40;   // board to board
constexpr double kBookSlot = 0.036;    // shelf width per book (mean thickness plus a gap)
constexpr double kBookLift = 0.001;    // books stand clear of the board (see above)
constexpr double kClear = 0.001;       // boards clear of the side panels
constexpr double kAboveFloor = 0.002;  // shelves and walls clear of the floor
constexpr double kLaneHeight = 0.02;
constexpr double kWallThickness = 0.3;
constexpr double kWallAboveShelves = 1.2;
constexpr uint32_t kBookMeshes = 4;

// A book standing on y = 0, centred in x and z, of unit thickness (x), height (y) and depth (z),
// spine towards +z: two covers, a page block set back from the covers' edges, a spine, and
// `bands` raised bands across the spine.
MeshData bookMesh(uint32_t bands, float cover) {
    MeshData m;
    const float spine = 0.05f;
    appendBox(m, {-0.5f, 0.0f, -0.5f}, {-0.5f + cover, 1.0f, 0.5f - spine});
    appendBox(m, {0.5f - cover, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f - spine});
    appendBox(m, {-0.5f + cover, 0.015f, -0.48f}, {0.5f - cover, 0.985f, 0.5f - spine});
    appendBox(m, {-0.5f, 0.0f, 0.5f - spine}, {0.5f, 1.0f, 0.5f});
    for (uint32_t b = 0; b < bands; ++b) {
        const float y = 0.12f + 0.76f * static_cast<float>(b) / static_cast<float>(bands - 1);
        appendBox(m, {-0.505f, y - 0.012f, 0.5f - spine}, {0.505f, y + 0.012f, 0.51f});
    }
    return m;
}

constexpr uint32_t kLibraryUnitBox = 0;  // the mesh every board, panel and wall is a scaled copy of
constexpr uint32_t kFirstBookMesh = 1;   // then kBookMeshes book meshes

// The room's measures, from the spec.
struct LibraryLayout {
    explicit LibraryLayout(const LibrarySpec& spec)
        : aisle(spec.aisle_width_m),
          pitch(kShelfDepth + aisle),
          unit(spec.books_per_level * kBookSlot + kSideThickness),
          row_length(spec.shelves_per_row * unit + kSideThickness),
          // The side panels rise 2 cm above the top board, so their tops and its top are not
          // coplanar.
          shelf_height(kFirstBoardY + spec.levels * kLevelPitch + kBoardThickness + 0.02),
          room_x0(-aisle),
          room_x1(row_length + aisle),
          room_z0(-aisle),
          room_z1((spec.rows - 1) * pitch + kShelfDepth + aisle),
          wall_height(shelf_height + kWallAboveShelves) {}
    double aisle, pitch, unit, row_length, shelf_height;
    double room_x0, room_x1, room_z0, room_z1, wall_height;
};

// Floor and walls. The walls along x run past the corners; those along z stop 1 cm short of
// them, so the corners show no crack and no two walls touch.
void addFloorAndWalls(const LibraryLayout& l, SourceOutput& out) {
    const double t = kWallThickness, f = kAboveFloor;
    out.objects.push_back(placeUnitBox(kLibraryUnitBox, {l.room_x0 - t, -0.2, l.room_z0 - t},
                                       {l.room_x1 + t, 0.0, l.room_z1 + t}));
    out.objects.push_back(placeUnitBox(kLibraryUnitBox, {l.room_x0 - 1.5 * t, f, l.room_z0 - t},
                                       {l.room_x1 + 1.5 * t, l.wall_height, l.room_z0}));
    out.objects.push_back(placeUnitBox(kLibraryUnitBox, {l.room_x0 - 1.5 * t, f, l.room_z1},
                                       {l.room_x1 + 1.5 * t, l.wall_height, l.room_z1 + t}));
    out.objects.push_back(placeUnitBox(kLibraryUnitBox, {l.room_x0 - t, f, l.room_z0 + 0.01},
                                       {l.room_x0, l.wall_height, l.room_z1 - 0.01}));
    out.objects.push_back(placeUnitBox(kLibraryUnitBox, {l.room_x1, f, l.room_z0 + 0.01},
                                       {l.room_x1 + t, l.wall_height, l.room_z1 - 0.01}));
}

// One board's row of books between inner0 and inner1 (x), standing on board_top, their backs
// towards z1. Thickness, height, depth, gap and set-back of each book are drawn before placing so
// the row can be squeezed to fit the board exactly when it comes out too wide.
void addBooks(const LibrarySpec& spec, double inner0, double inner1, double board_top, double z1,
              Rng& rng, SourceOutput& out) {
    struct Book {
        double thick, height, depth, gap, setback;
        uint32_t mesh;
    };
    std::vector<Book> books(spec.books_per_level);
    double total = 0.0;
    for (Book& b : books) {
        b.thick = rng.uniform(0.018, 0.048);
        b.height = rng.uniform() < 0.15 ? rng.uniform(0.30, 0.36) : rng.uniform(0.18, 0.29);
        b.depth = rng.uniform(0.14, 0.30);
        b.gap = rng.uniform(0.0015, 0.004);  // books never touch (see above)
        b.setback = rng.uniform(kBoardInset + 0.003, kBoardInset + 0.03);
        b.mesh = kFirstBookMesh + rng.below(kBookMeshes);
        total += b.thick + b.gap;
    }
    const double room = inner1 - inner0 - 0.004;
    const double squeeze = total > room ? room / total : 1.0;
    double x = inner0 + 0.002 + rng.uniform(0.0, std::max(0.0, room - total));
    for (const Book& b : books) {
        const double thick = b.thick * squeeze;
        PlacedObject book;
        book.mesh = b.mesh;
        book.position = {x + 0.5 * thick, board_top + kBookLift, z1 - b.setback - 0.5 * b.depth};
        book.linear = scaleMatrix(glm::vec3(static_cast<float>(thick), static_cast<float>(b.height),
                                            static_cast<float>(b.depth)));
        out.objects.push_back(book);
        x += thick + b.gap * squeeze;
    }
}

// Shelf unit u of row r: its side panels (one on the left of every unit, plus the last unit's
// right one), its boards, and the books on every board but the top one.
void addShelfUnit(const LibrarySpec& spec, const LibraryLayout& l, uint32_t r, uint32_t u, Rng& rng,
                  SourceOutput& out) {
    const double z0 = r * l.pitch, z1 = z0 + kShelfDepth;
    const double x0 = u * l.unit;  // left face of this unit's left side panel
    out.objects.push_back(placeUnitBox(kLibraryUnitBox, {x0, kAboveFloor, z0},
                                       {x0 + kSideThickness, l.shelf_height, z1}));
    if (u + 1 == spec.shelves_per_row) {
        out.objects.push_back(placeUnitBox(kLibraryUnitBox, {x0 + l.unit, kAboveFloor, z0},
                                           {x0 + l.unit + kSideThickness, l.shelf_height, z1}));
    }
    const double inner0 = x0 + kSideThickness + kClear, inner1 = x0 + l.unit - kClear;
    for (uint32_t level = 0; level <= spec.levels; ++level) {
        const double board_top = kFirstBoardY + level * kLevelPitch + kBoardThickness;
        out.objects.push_back(placeUnitBox(kLibraryUnitBox,
                                           {inner0, board_top - kBoardThickness, z0},
                                           {inner1, board_top, z1 - kBoardInset}));
        if (level == spec.levels) break;  // the top board carries no books
        addBooks(spec, inner0, inner1, board_top, z1, rng, out);
    }
}

}  // namespace

SourceOutput generateLibrary(const LibrarySpec& spec, uint64_t seed) {
    if (spec.rows == 0 || spec.shelves_per_row == 0 || spec.levels == 0 ||
        spec.books_per_level == 0 || !(spec.aisle_width_m > 0)) {
        throw std::invalid_argument("generateLibrary: invalid spec");
    }
    SourceOutput out;
    Rng rng(seed);
    const LibraryLayout l(spec);
    out.meshes.push_back(makeBox(glm::vec3(1.0f)));  // the unit box, mesh 0
    out.meshes.push_back(bookMesh(0, 0.12f));        // the book meshes, from kFirstBookMesh
    out.meshes.push_back(bookMesh(2, 0.10f));
    out.meshes.push_back(bookMesh(3, 0.14f));
    out.meshes.push_back(bookMesh(2, 0.18f));
    addFloorAndWalls(l, out);
    for (uint32_t r = 0; r < spec.rows; ++r) {
        for (uint32_t u = 0; u < spec.shelves_per_row; ++u) addShelfUnit(spec, l, r, u, rng, out);
    }
    // One loop round each row, 3/8 of an aisle out from its shelves, clockwise seen from above.
    const double d = 0.375 * l.aisle, y = kLaneHeight;
    for (uint32_t r = 0; r < spec.rows; ++r) {
        const double z0 = r * l.pitch - d, z1 = r * l.pitch + kShelfDepth + d;
        out.lanes.push_back(
            {{-d, y, z0}, {l.row_length + d, y, z0}, {l.row_length + d, y, z1}, {-d, y, z1}});
    }
    out.region = sourceBounds(out);
    return out;
}

}  // namespace occsim
