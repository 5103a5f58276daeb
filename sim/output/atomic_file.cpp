#include "sim/output/atomic_file.h"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace occsim {
namespace {

// "cannot write <path>: <the OS reason>", as every write error says it.
std::string cannotWrite(const std::filesystem::path& path, const std::string& reason) {
    return "cannot write " + path.string() + ": " + reason;
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, std::string_view contents) {
    std::filesystem::path temp = path;
    temp += ".tmp." + std::to_string(::getpid());
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (f == nullptr) throw std::runtime_error(cannotWrite(path, std::strerror(errno)));
    // errno is read at once: the cleanup below may change it.
    int error = 0;
    if (std::fwrite(contents.data(), 1, contents.size(), f) != contents.size()) error = errno;
    if (std::fclose(f) != 0 && error == 0) error = errno;
    std::error_code ec;
    if (error != 0) {
        std::filesystem::remove(temp, ec);
        throw std::runtime_error(cannotWrite(path, std::strerror(error)));
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        const std::string reason = ec.message();
        std::filesystem::remove(temp, ec);
        throw std::runtime_error(cannotWrite(path, reason));
    }
}

void writeFileAtomically(const std::filesystem::path& path, const std::vector<uint8_t>& contents) {
    writeFileAtomically(
        path, std::string_view(reinterpret_cast<const char*>(contents.data()), contents.size()));
}

std::string safeFileName(std::string_view label) {
    std::string out(label);
    for (char& c : out) {
        // '+' stays: culler names carry it (statistical+, chc++), and it needs no quoting.
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.' && c != '_' &&
            c != '+')
            c = '_';
    }
    if (!out.empty() && out.front() == '.') out.front() = '_';
    return out.empty() ? "_" : out;
}

std::string distinctFileName(std::string_view label) {
    const std::string safe = safeFileName(label);
    if (safe == label) return safe;
    uint32_t h = 2166136261u;  // FNV-1a
    for (unsigned char c : label) {
        h ^= c;
        h *= 16777619u;
    }
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", h);
    return safe + "-" + hex;
}

}  // namespace occsim
