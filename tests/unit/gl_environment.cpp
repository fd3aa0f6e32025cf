// One headless context per GL test binary; see gl_environment.h.
#include "tests/unit/gl_environment.h"

#include <gtest/gtest.h>

#include <exception>
#include <memory>
#include <stdexcept>

namespace lp::test {
namespace {

class GlEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
    // Headless: no default framebuffer is drawn to (every test renders into its own
    // targets), so the requested size only matters to a window and is kept small.
    try {
      context_ = Context::create({.headless = true, .width = 64, .height = 64});
    } catch (const std::exception& e) {
      // A fatal failure here makes GoogleTest skip every test and report this one reason.
      GTEST_FAIL() << "no OpenGL context for the GL tests: " << e.what();
    }
  }
  void TearDown() override { context_.reset(); }  // after every fixture's TearDownTestSuite
  Context* context() const { return context_.get(); }

 private:
  std::unique_ptr<Context> context_;
};

// Registered before main (gtest_main's) runs; GoogleTest owns and deletes it.
GlEnvironment* const environment =
    static_cast<GlEnvironment*>(::testing::AddGlobalTestEnvironment(new GlEnvironment));

}  // namespace

Context& gl_context() {
  Context* c = environment->context();
  if (!c) throw std::logic_error("lp::test::gl_context() outside the GL test environment");
  return *c;
}

}  // namespace lp::test
