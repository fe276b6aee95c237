// Output files written so that a path planted in the output directory cannot redirect them: each file is
// written under a fresh name beside its destination and renamed over it, which replaces an existing symlink
// (or file) instead of following it, and never leaves a half-written file under the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace vct {

// Calls `write(temporary)` to make the file under a fresh name in `path`'s directory, then renames it to
// `path`. Throws vct::Error naming `path` when the directory is missing or not writable; whatever `write`
// throws propagates (the temporary file is removed).
void writeReplacing(const std::filesystem::path& path,
                    const std::function<void(const std::filesystem::path&)>& write);

// `text` into `path` the same way.
void writeTextReplacing(const std::filesystem::path& path, const std::string& text);

// Makes `dir` (and its parents) an output directory before any work is done: a usage error names `flag` when
// it exists but is not a directory, an Error when it cannot be created.
void prepareOutputDirectory(const std::filesystem::path& dir, const std::string& flag);

}  // namespace vct
