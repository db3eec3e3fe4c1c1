// For the vector loops built for one target alone (tests/CMakeLists.txt): skips every test
// where this processor cannot run that target's instructions.

#include <gtest/gtest.h>

namespace {

class VectorTargetGuard : public testing::Environment {
 public:
  void SetUp() override {
#if defined(ECO_VECTOR_TARGET_AVX2)
    if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this processor has no AVX2";
#endif
  }
};

[[maybe_unused]] testing::Environment* const guard = testing::AddGlobalTestEnvironment(new VectorTargetGuard);

}  // namespace
