// Output files written so that a path planted in the output directory cannot redirect them: each file is
// made in memory, written under a fresh name beside its destination (every write checked, fsync'ed) and
// renamed over it, which replaces an existing symlink (or file) instead of following it, and never leaves a
// half-written file under the final name. The writing itself is writeFileReplacing (scene/input_limits.h),
// which the scene layer's writers use directly.
#pragma once

#include <filesystem>
#include <string>

#include "scene/input_limits.h"

namespace vct {

// `text` into `path` through writeFileReplacing.
void writeTextReplacing(const std::filesystem::path& path, const std::string& text);

// Makes `dir` (and its parents) an output directory before any work is done: a usage error names `flag` when
// it exists but is not a directory, an Error when it cannot be created.
void prepareOutputDirectory(const std::filesystem::path& dir, const std::string& flag);

// Whether `path`, made absolute and normalised, lies under `dir` (also normalised): what confines the outputs
// a script names to its output directory.
bool pathWithin(const std::filesystem::path& path, const std::filesystem::path& dir);

}  // namespace vct
