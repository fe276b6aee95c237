#include "scene/input_limits.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

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

FileRead readRegularFile(const std::filesystem::path& path, uint64_t maxBytes) {
    FileRead result;
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer; the type is checked on the
    // descriptor, so nothing can swap the path in between.
    const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        result.error = errno == ENOENT ? "no such file" : std::strerror(errno);
        return result;
    }
    struct stat info {};
    if (fstat(fd, &info) != 0) {
        result.error = std::strerror(errno);
    } else if (auto problem = statProblem(info, maxBytes)) {
        result.error = *problem;
    } else {
        result.bytes.resize(size_t(info.st_size));
        size_t done = 0;
        while (done < result.bytes.size()) {
            const ssize_t n = read(fd, result.bytes.data() + done, result.bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                result.error = n < 0 ? std::strerror(errno) : "shorter than its size (changed while read?)";
                break;
            }
            done += size_t(n);
        }
    }
    close(fd);
    if (!result.error.empty()) result.bytes = {};
    return result;
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
