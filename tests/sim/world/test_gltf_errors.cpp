// Broken glTF files fail with one line naming the file and what was expected: missing, truncated or
// corrupt files, accessors and indices out of range, non-finite positions, cycles, and occluder
// roles or meshes that name nothing of the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "gltf_files.h"

namespace occsim {
namespace {

using nlohmann::json;
using namespace testing_gltf;
using namespace gltf_files;

TEST(GltfErrors, AnOccluderRoleThatIsNotOneOfTheThreeNamesTheNode) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    b.node({{"mesh", mesh}});
    b.node({{"mesh", mesh}, {"name", "Wall"}, {"extras", {{"occsim_occluder", "yes"}}}});
    const std::string message = errorOfText(b.text());
    EXPECT_NE(message.find("model.gltf: node 1 ('Wall'): extras.occsim_occluder: expected "
                           "\"always\", \"never\" or \"by_size\", got \"yes\""),
              std::string::npos)
        << message;
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0);
}
TEST(GltfErrors, AnOccluderMeshThatIsNoMeshOfTheFileNamesTheNode) {
    for (const json& bad : {json(5), json(-1), json(0.5), json("Inner")}) {
        GltfBuilder b;
        const int mesh = b.triangleMesh("Tri");
        b.node({{"mesh", mesh}, {"name", "Wall"}, {"extras", {{"occsim_occluder_mesh", bad}}}});
        const std::string message = errorOfText(b.text());
        EXPECT_NE(message.find("model.gltf: node 0 ('Wall'): extras.occsim_occluder_mesh: expected "
                               "the index of one of the file's 1 mesh, got "),
                  std::string::npos)
            << message;
        EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0);
        if (bad == json(5)) {
            EXPECT_NE(message.find("got 5"), std::string::npos) << message;
        }
        if (bad.is_string()) {
            EXPECT_NE(message.find("got \"Inner\""), std::string::npos) << message;
        }
    }
}
// `file` is the path, or the end of it, that the message must start with.
void expectOneLineError(const std::string& error, const std::string& file,
                        const std::string& part) {
    ASSERT_FALSE(error.empty()) << "expected a GltfError";
    const size_t at = error.find(file + ": ");
    ASSERT_NE(at, std::string::npos) << error;
    EXPECT_EQ(error.find(": "), at + file.size()) << "the message starts with the file: " << error;
    EXPECT_NE(error.find(part), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

TEST(GltfErrors, MissingFile) {
    const std::filesystem::path missing = kAssets / "no-such-model.glb";
    expectOneLineError(errorOf(missing), missing.string(), "no such file");
}

TEST(GltfErrors, TruncatedGlb) {
    std::ifstream in(kHouse, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 1000u);
    TempDir dir;
    const std::filesystem::path half = dir.write("half.glb", bytes.substr(0, bytes.size() / 2));
    expectOneLineError(errorOf(half), half.string(), "");
}

TEST(GltfErrors, CorruptJson) {
    TempDir dir;
    const std::filesystem::path file =
        dir.write("corrupt.gltf", R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [)");
    expectOneLineError(errorOf(file), file.string(), "");
}

TEST(GltfErrors, MissingExternalBin) {
    GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    json doc = json::parse(b.text());
    doc["buffers"][0]["uri"] = "missing.bin";
    TempDir dir;
    const std::filesystem::path file = dir.write("external.gltf", doc.dump());
    expectOneLineError(errorOf(file), file.string(), "missing.bin");
}

TEST(GltfErrors, ExternalBinLoadsWhenPresent) {
    GltfBuilder b;
    b.node({{"mesh", b.triangleMesh("Tri")}});
    json doc = json::parse(b.text());
    doc["buffers"][0]["uri"] = "model.bin";
    TempDir dir;
    dir.write("model.bin", std::string(b.bytes().begin(), b.bytes().end()));
    const SourceOutput out = load(dir.write("external.gltf", doc.dump()));
    EXPECT_EQ(drawnTriangles(out), 1u);
}

TEST(GltfErrors, AccessorIndexOutOfRange) {
    GltfBuilder b;
    b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});  // accessor 0 exists
    b.node({{"mesh", b.mesh("Bad", json::array({GltfBuilder::primitive(7)}))}});
    expectOneLineError(errorOfText(b.text()), "model.gltf", "accessor 7");
}

TEST(GltfErrors, IndexValuePastTheVertexCount) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    b.node(
        {{"mesh", b.mesh("Bad", json::array({GltfBuilder::primitive(p, b.indices({0, 1, 3}))}))}});
    expectOneLineError(errorOfText(b.text()), "model.gltf", "index value 3");
}

TEST(GltfErrors, NonFinitePosition) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {NAN, 0, 0}, {0, 1, 0}});
    b.node({{"mesh", b.mesh("Bad", json::array({GltfBuilder::primitive(p)}))}});
    // nlohmann writes NaN bounds as null; drop them (they are optional) to reach our check.
    b.doc()["accessors"][p].erase("min");
    b.doc()["accessors"][p].erase("max");
    expectOneLineError(errorOfText(b.text()), "model.gltf", "not finite");
}

TEST(GltfErrors, AccessorPastTheEndOfItsBufferView) {
    GltfBuilder b;
    const int p = b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    b.doc()["accessors"][p]["count"] = 4;
    b.node({{"mesh", b.mesh("Bad", json::array({GltfBuilder::primitive(p)}))}});
    expectOneLineError(errorOfText(b.text()), "model.gltf", "runs past the end");
}

TEST(GltfErrors, NodeHierarchyCycle) {
    GltfBuilder b;
    const int mesh = b.triangleMesh("Tri");
    b.node({{"mesh", mesh}, {"children", {1}}});
    b.node({{"mesh", mesh}, {"children", {0}}}, false);
    expectOneLineError(errorOfText(b.text()), "model.gltf", "cycle");
}

}  // namespace
}  // namespace occsim
