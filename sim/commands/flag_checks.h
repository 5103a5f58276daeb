// The checks on flag values that CLI11 cannot make, shared by the commands. The idiom is one:
// a value is checked once, before any work, and a bad one throws occsim::InputError whose line
// starts with the flag ("--algos: 'vfc' is listed twice"); integerIn() is the same check made by
// CLI11 while parsing, with the same kind of line.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "occsim/culling/registry/registry.h"

namespace occsim_cli {

// A whole number in [lo, hi], checked on the text before CLI11 converts it.
CLI::Validator integerIn(long long lo, long long hi);

// The registered algorithm `name`, given by `flag`.
const occsim::CullerRow& algorithmNamed(const std::string& flag, const std::string& name);

// An output path is checked before any work, so that a run never ends on a path it cannot
// write: a folder flag must not name a file, a file flag not a folder, and neither may be empty
// when given.
void checkOutputFolder(const std::string& flag, const std::string& path, bool given);
void checkOutputFile(const std::string& flag, const std::string& path, bool given);

// --record as given (comma-separated, repeatable): true when it asks for objects (the only kind
// there is); an empty list is false. Throws occsim::InputError for a value not listed.
bool recordsObjects(const std::vector<std::string>& values);
// --record's help text: what it takes and does.
inline constexpr const char* kRecordHelp =
    "Record more of the run: 'objects' writes objects.sqlite into the run folder (every object's "
    "decision per frame and configuration, the culler's reason and ground truth's pixels; "
    "measures error as --error does; occsim why reads it)";
// A file or folder the command will write at its end, checked before any work (symlinks followed):
// it, or the nearest folder above it that exists, can be written by this process. Throws
// InputError starting with the flag.
void checkWritableFile(const std::string& flag, const std::string& path);
void checkWritableFolder(const std::string& flag, const std::string& path);

// Whether `inner` is `outer` or lies below it (both made absolute, symlinks followed).
bool sameOrInside(const std::filesystem::path& inner, const std::filesystem::path& outer);

// Whether both exist and are one folder (an --out that would overwrite its input).
bool sameFolder(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace occsim_cli
