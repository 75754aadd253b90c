// The build rounds every multiply and add on its own: the structures' tests
// compare SIMD and scalar traversals and brute force to the bit, and a
// compiler that fuses a * b + c into one rounding where the target has FMA
// (GCC's default, -ffp-contract=fast) breaks that on such CPUs.
#include <gtest/gtest.h>

namespace {

#if defined(__x86_64__) || defined(__i386__)
// Built for a target with FMA, as -march=native or a function's AVX-512
// target would: the compiler may fuse here unless the build forbids it.
__attribute__((target("fma"), noinline)) float multiplyAdd(float a, float b, float c) { return a * b + c; }

TEST(FloatRounding, MultiplyAndAddRoundSeparatelyWhereTheTargetHasFma) {
  if (!__builtin_cpu_supports("fma")) GTEST_SKIP() << "this CPU has no FMA";
  // a * a = 1 + 2^-11 + 2^-24 exactly; rounded to float it is 1 + 2^-11 (a tie,
  // to even), so a * a - (1 + 2^-11) is 0, and 2^-24 when fused.
  volatile float a = 1.0f + 0x1p-12f, c = -(1.0f + 0x1p-11f);
  EXPECT_EQ(multiplyAdd(a, a, c), 0.0f) << "a * b + c was fused: build with -ffp-contract=off";
}
#endif

}  // namespace
