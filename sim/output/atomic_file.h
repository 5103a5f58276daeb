// Output files appear whole or not at all: written to a temporary file beside the target, then
// renamed over it (rename is atomic within a file system).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace occsim {

// Throws std::runtime_error "cannot write <path>: <the OS reason>" on any failure; never leaves a
// partial target.
void writeFileAtomically(const std::filesystem::path& path, std::string_view contents);
void writeFileAtomically(const std::filesystem::path& path, const std::vector<uint8_t>& contents);

// A label made safe as one file-name component: letters, digits, '-', '_', '+' and '.' are kept,
// anything else becomes '_', and a leading '.' too (no hidden files, no ".."); an empty label is
// "_", so that the result is always one path component.
std::string safeFileName(std::string_view label);

// safeFileName(), and when that changed the label, "-" and 8 hex digits of a hash of the label:
// two labels that differ only in what safeFileName() replaces ("a b", "a/b", "ä", "ö") still name
// two files.
std::string distinctFileName(std::string_view label);

}  // namespace occsim
