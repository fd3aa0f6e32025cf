#pragma once
// The OpenGL context of a GL test binary. One GoogleTest environment makes a headless
// lp::Context before the first test and destroys it after the last one, after every fixture's
// TearDownTestSuite has released its GL objects. Fixtures make no context of their own: their
// GL objects live in the current one. Linking gl_environment.cpp registers it (tests/CMakeLists.txt
// adds it to every binary of kind `gl`).
#include "common/context.h"

namespace lp::test {

// The binary's context. Only valid while tests run (the environment made it).
Context& gl_context();

}  // namespace lp::test
