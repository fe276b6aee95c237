#include "io/safe_write.h"

#include "core/error.h"

namespace vct {

void writeTextReplacing(const std::filesystem::path& path, const std::string& text) {
    writeFileReplacing(path, text);
}

void prepareOutputDirectory(const std::filesystem::path& dir, const std::string& flag) {
    std::error_code error;
    if (std::filesystem::exists(dir, error) && !std::filesystem::is_directory(dir, error))
        throw UsageError(flag + " '" + dir.string() + "' exists and is not a directory");
    std::filesystem::create_directories(dir, error);
    if (error) throw Error("cannot create output directory '" + dir.string() + "': " + error.message());
}

bool pathWithin(const std::filesystem::path& path, const std::filesystem::path& dir) {
    const std::filesystem::path p = std::filesystem::absolute(path).lexically_normal();
    const std::filesystem::path d = std::filesystem::absolute(dir).lexically_normal();
    const std::filesystem::path relative = p.lexically_relative(d);
    return !relative.empty() && *relative.begin() != ".." && relative != ".";
}

}  // namespace vct
