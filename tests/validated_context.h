// The device of the tests that render in process (not through the vct program): one per test binary, with the
// validation layer on; each test checks that vk::validationMessageCount() did not grow while it ran.
// Header-only (tests/CMakeLists.txt builds only *_test.cpp files).
#pragma once

#include "vk/context.h"

namespace vct::test {

inline vk::Context& validatedContext() {
    static vk::Context* instance = [] {
        vk::ContextOptions options;
        options.validation = true;
        return new vk::Context(options);  // never destroyed: tests in any order, at exit too
    }();
    return *instance;
}

}  // namespace vct::test
