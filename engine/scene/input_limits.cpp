#include "scene/input_limits.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/error.h"

namespace vct {

namespace {

const char* fileTypeName(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a plain file";
}

// The mode a plainly created file would get (0666 less the umask); mkstemp makes 0600.
mode_t createdFileMode() {
    static const mode_t mode = [] {
        const mode_t mask = umask(0);
        umask(mask);
        return mode_t(0666 & ~mask);
    }();
    return mode;
}

std::optional<std::string> statProblem(const struct stat& info, uint64_t maxBytes) {
    if (!S_ISREG(info.st_mode)) return std::string("not a regular file (") + fileTypeName(info.st_mode) + ")";
    if (uint64_t(info.st_size) > maxBytes)
        return "is " + byteSizeText(uint64_t(info.st_size)) + ", more than the " + byteSizeText(maxBytes) +
               " an input file may have";
    return std::nullopt;
}

}  // namespace

std::string byteSizeText(uint64_t bytes) {
    char text[32];
    if (bytes < 10'000)
        std::snprintf(text, sizeof(text), "%llu bytes", (unsigned long long)bytes);
    else if (bytes < 10'000'000)
        std::snprintf(text, sizeof(text), "%.1f kB", double(bytes) / 1e3);
    else if (bytes < 10'000'000'000ull)
        std::snprintf(text, sizeof(text), "%.1f MB", double(bytes) / 1e6);
    else
        std::snprintf(text, sizeof(text), "%.1f GB", double(bytes) / 1e9);
    return text;
}

std::string numberText(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
}

std::optional<std::string> regularFileProblem(const std::filesystem::path& path, uint64_t maxBytes) {
    struct stat info {};
    if (stat(path.c_str(), &info) != 0)
        return std::string(errno == ENOENT ? "no such file" : std::strerror(errno));
    return statProblem(info, maxBytes);
}

InputFile::InputFile(const std::filesystem::path& path, uint64_t maxBytes) {
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer; the type is checked on the
    // descriptor, so nothing can swap the path in between.
    fd_ = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) {
        error_ = errno == ENOENT ? "no such file" : std::strerror(errno);
        return;
    }
    struct stat info {};
    if (fstat(fd_, &info) != 0)
        error_ = std::strerror(errno);
    else if (auto problem = statProblem(info, maxBytes))
        error_ = *problem;
    else
        size_ = uint64_t(info.st_size);
}

InputFile::~InputFile() {
    if (fd_ >= 0) close(fd_);
}

std::string InputFile::readAt(uint64_t offset, uint64_t length, std::vector<unsigned char>& out) const {
    if (!error_.empty()) return error_;
    if (!rangeWithin(offset, length, size_)) return "shorter than its size (changed while read?)";
    out.resize(size_t(length));
    size_t done = 0;
    while (done < out.size()) {
        const ssize_t n = pread(fd_, out.data() + done, out.size() - done, off_t(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            out = {};
            return n < 0 ? std::strerror(errno) : "shorter than its size (changed while read?)";
        }
        done += size_t(n);
    }
    return {};
}

FileRead readRegularFile(const std::filesystem::path& path, uint64_t maxBytes) {
    FileRead result;
    const InputFile file(path, maxBytes);
    result.error = file.error();
    if (result.error.empty()) result.error = file.readAt(0, file.size(), result.bytes);
    if (!result.error.empty()) result.bytes = {};
    return result;
}

void writeFileReplacing(const std::filesystem::path& path, std::string_view bytes) {
    auto fail = [&](const std::string& why) { throw Error("cannot write " + path.string() + ": " + why); };
    struct stat existing {};
    if (lstat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode) && !S_ISLNK(existing.st_mode))
        fail(std::string("it exists and is not a regular file (") + fileTypeName(existing.st_mode) + ")");
    const std::filesystem::path dir =
        path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    std::string pattern = (dir / ("." + path.filename().string() + ".XXXXXX")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    const int fd = mkstemp(name.data());  // O_EXCL: a fresh regular file, never something planted
    if (fd < 0) fail(std::strerror(errno));
    fchmod(fd, createdFileMode());
    std::string problem;
    for (size_t done = 0; done < bytes.size() && problem.empty();) {
        const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            problem = n < 0 ? std::strerror(errno) : "nothing written";
        else
            done += size_t(n);
    }
    if (problem.empty() && fsync(fd) != 0) problem = std::strerror(errno);
    if (close(fd) != 0 && problem.empty()) problem = std::strerror(errno);
    if (problem.empty() && std::rename(name.data(), path.c_str()) != 0) problem = std::strerror(errno);
    if (!problem.empty()) {
        unlink(name.data());
        fail(problem);
    }
}

std::string printableText(std::string_view text, size_t maxChars) {
    std::string out;
    for (unsigned char c : text) {
        if (c == '\n') {
            out += "\\n";
        } else if (c == '\r') {
            out += "\\r";
        } else if (c == '\t') {
            out += "\\t";
        } else if (c < 0x20 || c == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof(hex), "\\x%02x", c);
            out += hex;
        } else {
            out += char(c);
        }
    }
    if (out.size() > maxChars) {
        const size_t keep = maxChars / 2;
        out = out.substr(0, keep) + " [... " + std::to_string(out.size() - 2 * keep) + " characters] " +
              out.substr(out.size() - keep);
    }
    return out;
}

int jsonNestingDepth(std::string_view text, int limit) {
    int depth = 0, deepest = 0;
    bool inString = false, escaped = false;
    for (char c : text) {
        if (inString) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            if (deepest > limit) return deepest;
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return deepest;
}

}  // namespace vct
