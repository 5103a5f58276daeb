// Checked views of glTF accessors: every reference and byte range is validated before a byte is
// read, so a broken file is an error and never a read past a buffer.
#include "sim/scene/gltf_detail.h"

namespace occsim::gltf_detail {

[[noreturn]] void fail(const std::string& file, const std::string& reason) {
    throw GltfError(file + ": " + reason);
}

std::string plural(size_t n, const std::string& word) {
    return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

// Checks every reference and byte range of accessor `index` (used as `what`); a broken file
// throws, a valid accessor this loader does not read (sparse, no bufferView) is a skip.
ViewOrSkip viewAccessor(const Context& c, int index, const std::string& what) {
    const tg::Model& m = c.model;
    if (index < 0 || static_cast<size_t>(index) >= m.accessors.size()) {
        fail(c.file, what + " refers to accessor " + std::to_string(index) + ", but the file has " +
                         plural(m.accessors.size(), "accessor"));
    }
    const tg::Accessor& a = m.accessors[static_cast<size_t>(index)];
    const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    if (a.sparse.isSparse) return {std::nullopt, "sparse accessors"};
    if (a.bufferView < 0) return {std::nullopt, "accessors without a bufferView"};
    if (static_cast<size_t>(a.bufferView) >= m.bufferViews.size()) {
        fail(c.file, name + " refers to bufferView " + std::to_string(a.bufferView) +
                         ", but the file has " + plural(m.bufferViews.size(), "bufferView"));
    }
    const tg::BufferView& bv = m.bufferViews[static_cast<size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= m.buffers.size()) {
        fail(c.file, "bufferView " + std::to_string(a.bufferView) + " refers to buffer " +
                         std::to_string(bv.buffer) + ", but the file has " +
                         plural(m.buffers.size(), "buffer"));
    }
    const std::vector<unsigned char>& bytes = m.buffers[static_cast<size_t>(bv.buffer)].data;
    if (bv.byteOffset > bytes.size() || bv.byteLength > bytes.size() - bv.byteOffset) {
        fail(c.file, "bufferView " + std::to_string(a.bufferView) +
                         " runs past the end of buffer " + std::to_string(bv.buffer));
    }
    const int component_size = tg::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
    const int components = tg::GetNumComponentsInType(static_cast<uint32_t>(a.type));
    const int stride = a.ByteStride(bv);
    if (component_size <= 0 || components <= 0 || stride < component_size * components) {
        fail(c.file, name + " has an invalid type, componentType or byteStride");
    }
    const auto element = static_cast<size_t>(component_size * components);
    // Compared step by step so that a huge count or offset cannot overflow the arithmetic.
    if (a.count > 0 &&
        (a.byteOffset > bv.byteLength ||
         a.count - 1 > bv.byteLength / static_cast<size_t>(stride) ||
         a.byteOffset + (a.count - 1) * static_cast<size_t>(stride) + element > bv.byteLength)) {
        fail(c.file, name + " runs past the end of bufferView " + std::to_string(a.bufferView));
    }
    AccessorView view;
    view.data = bytes.data() + bv.byteOffset + a.byteOffset;
    view.stride = static_cast<size_t>(stride);
    view.count = a.count;
    view.component_type = a.componentType;
    view.type = a.type;
    view.normalized = a.normalized;
    return {view, {}};
}

}  // namespace occsim::gltf_detail
