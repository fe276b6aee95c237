// The one progress line of long commands (benchmark, reference) on stderr, redrawn in place:
// "LABEL [#####...............]  25% DETAIL". stdout keeps the tables and file names.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>

namespace vct {

inline void printProgressLine(const char* label, int percent, const std::string& detail) {
    percent = std::clamp(percent, 0, 100);
    const std::string bar =
        std::string(size_t(percent / 5), '#') + std::string(size_t(20 - percent / 5), '.');
    std::fprintf(stderr, "\r%s [%s] %3d%% %s", label, bar.c_str(), percent, detail.c_str());
    std::fflush(stderr);
}

}  // namespace vct
