#include "sim/record/object_database.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>

#include "sim/record/object_schema.h"

namespace occsim {
namespace {

uint32_t bigEndian(const unsigned char* p, int bytes) {
    uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | p[i];
    return v;
}

std::string hint() { return "; record the run again with --record objects"; }

// SQLite's words on one line (an integrity report can span several).
std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

}  // namespace

// The 100-byte header of the SQLite file format: the magic string, the page size (offset 16) and,
// when the header's change counter (offset 24) matches its version-valid-for number (offset 92),
// the database's size in pages (offset 28).
std::string sqliteFileProblem(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 100> h{};
    in.read(reinterpret_cast<char*>(h.data()), static_cast<std::streamsize>(h.size()));
    const auto got = static_cast<size_t>(in.gcount());
    static constexpr char kMagic[] = "SQLite format 3";
    if (got < 16 || std::memcmp(h.data(), kMagic, sizeof kMagic) != 0) {
        return got == 0 ? "empty; expected an SQLite database" : "not an SQLite database";
    }
    if (got < h.size())
        return "truncated: " + std::to_string(got) + " bytes, shorter than its header";
    uint32_t page_size = bigEndian(&h[16], 2);
    if (page_size == 1) page_size = 65536;
    const uint32_t pages = bigEndian(&h[28], 4);
    const bool size_valid = bigEndian(&h[24], 4) == bigEndian(&h[92], 4) && pages > 0;
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(file, ec);
    const uintmax_t declared = uintmax_t{page_size} * pages;
    if (!ec && size_valid && size < declared) {
        return "truncated: " + std::to_string(size) + " bytes of the " + std::to_string(declared) +
               " its header declares";
    }
    return "";
}

ObjectDatabase::ObjectDatabase(const std::filesystem::path& run_folder)
    : file_(run_folder / kObjectsDatabaseFile) {
    namespace fs = std::filesystem;
    const std::string folder = run_folder.string();
    if (!fs::is_directory(run_folder)) {
        throw ObjectsDatabaseError(folder +
                                   ": no such folder; expected a run folder (occsim "
                                   "run|bench|regress --out, recorded with --record objects)");
    }
    if (!fs::is_regular_file(file_)) {
        throw ObjectsDatabaseError(folder + ": no " + kObjectsDatabaseFile +
                                   "; expected a run recorded with --record objects (occsim "
                                   "run|bench|regress ... --record objects)");
    }
    const std::string name = file_.string();
    if (const std::string problem = sqliteFileProblem(file_); !problem.empty())
        throw ObjectsDatabaseError(name + ": " + problem + hint());
    try {
        db_ = std::make_unique<sql::Database>(file_, sql::Database::Mode::ReadOnly);
        sql::Statement check = db_->prepare("PRAGMA quick_check(1)");
        if (check.step() && check.text(0) != "ok") {
            throw ObjectsDatabaseError(name + ": corrupt (" + oneLine(check.text(0)) + ")" +
                                       hint());
        }
        sql::Statement has_run = db_->prepare(
            "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = 'run'");
        has_run.step();
        if (has_run.integer(0) == 0) {
            throw ObjectsDatabaseError(name +
                                       ": an SQLite database without occsim's run table; "
                                       "expected objects.sqlite as --record objects writes it");
        }
        sql::Statement version = db_->prepare("SELECT format_version, occsim_version FROM run");
        if (!version.step()) {
            throw ObjectsDatabaseError(name + ": its run table is empty" + hint());
        }
        run_.format_version = static_cast<int>(version.integer(0));
        run_.occsim_version = version.text(1);
        if (run_.format_version != kObjectsFormatVersion || run_.occsim_version != OCCSIM_VERSION) {
            throw ObjectsDatabaseError(name + ": written by occsim " + run_.occsim_version +
                                       " (database format " + std::to_string(run_.format_version) +
                                       "); this is occsim " + OCCSIM_VERSION + " (format " +
                                       std::to_string(kObjectsFormatVersion) +
                                       "): expected a database this version wrote" + hint());
        }
        sql::Statement r = db_->prepare(
            "SELECT command, scenario, frames, frames_recorded, partial, partial_reason, "
            "deterministic_latency, repetitions FROM run");
        r.step();
        run_.command = r.text(0);
        run_.scenario = r.text(1);
        run_.frames = static_cast<uint32_t>(r.integer(2));
        run_.frames_recorded = static_cast<uint32_t>(r.integer(3));
        run_.partial = r.integer(4) != 0;
        run_.partial_reason = r.text(5);
        if (!r.isNull(6)) run_.deterministic_latency = static_cast<uint32_t>(r.integer(6));
        run_.repetitions = static_cast<uint32_t>(r.integer(7));
    } catch (const sql::Error& e) {
        std::string why = e.what();
        if (why.rfind(name + ": ", 0) == 0) why = why.substr(name.size() + 2);
        throw ObjectsDatabaseError(name + ": unreadable (" + oneLine(why) + ")" + hint());
    }
}

}  // namespace occsim
