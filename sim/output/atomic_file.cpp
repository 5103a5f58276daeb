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

void writeFileAtomically(const std::filesystem::path& path, std::string_view contents) {
    std::filesystem::path temp = path;
    temp += ".tmp." + std::to_string(::getpid());
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (f == nullptr)
        throw std::runtime_error(path.string() + ": cannot write (" + std::strerror(errno) + ")");
    const bool written = std::fwrite(contents.data(), 1, contents.size(), f) == contents.size();
    const bool closed = std::fclose(f) == 0;
    std::error_code ec;
    if (!written || !closed) {
        std::filesystem::remove(temp, ec);
        throw std::runtime_error(path.string() + ": write failed");
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        throw std::runtime_error(path.string() + ": cannot rename the temporary file into place");
    }
}

void writeFileAtomically(const std::filesystem::path& path, const std::vector<uint8_t>& contents) {
    writeFileAtomically(
        path, std::string_view(reinterpret_cast<const char*>(contents.data()), contents.size()));
}

std::string safeFileName(std::string_view label) {
    std::string out(label);
    for (char& c : out) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.' && c != '_')
            c = '_';
    }
    if (!out.empty() && out.front() == '.') out.front() = '_';
    return out;
}

}  // namespace occsim
