#include "io/safe_write.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/error.h"

namespace vct {

namespace {

// The mode a plainly created file would get (0666 less the umask); mkstemp makes 0600.
mode_t createdFileMode() {
    static const mode_t mode = [] {
        const mode_t mask = umask(0);
        umask(mask);
        return mode_t(0666 & ~mask);
    }();
    return mode;
}

}  // namespace

void writeReplacing(const std::filesystem::path& path,
                    const std::function<void(const std::filesystem::path&)>& write) {
    const std::filesystem::path dir =
        path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    std::string pattern = (dir / ("." + path.filename().string() + ".XXXXXX")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int fd = mkstemp(name.data());  // O_EXCL: a fresh regular file, never something planted
    if (fd < 0) throw Error("cannot write " + path.string() + ": " + std::strerror(errno));
    fchmod(fd, createdFileMode());
    close(fd);
    const std::filesystem::path temporary(name.data());
    try {
        write(temporary);
        if (std::rename(temporary.c_str(), path.c_str()) != 0)
            throw Error("cannot write " + path.string() + ": " + std::strerror(errno));
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw;
    }
}

void writeTextReplacing(const std::filesystem::path& path, const std::string& text) {
    writeReplacing(path, [&](const std::filesystem::path& temporary) {
        FILE* file = std::fopen(temporary.c_str(), "wb");
        const bool ok = file && std::fwrite(text.data(), 1, text.size(), file) == text.size();
        if (file && std::fclose(file) != 0)
            throw Error("cannot write " + path.string() + ": " + std::strerror(errno));
        if (!ok) throw Error("cannot write " + path.string() + ": " + std::strerror(errno));
    });
}

void prepareOutputDirectory(const std::filesystem::path& dir, const std::string& flag) {
    std::error_code error;
    if (std::filesystem::exists(dir, error) && !std::filesystem::is_directory(dir, error))
        throw UsageError(flag + " '" + dir.string() + "' exists and is not a directory");
    std::filesystem::create_directories(dir, error);
    if (error) throw Error("cannot create output directory '" + dir.string() + "': " + error.message());
}

}  // namespace vct
