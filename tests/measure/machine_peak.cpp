// This machine's limits for the roofline (scripts/bench_speed.py): FP32 peak
// by independent FMA chains (AVX-512, AVX2+FMA or scalar, chosen at run time)
// on N threads, and memory bandwidth by a STREAM triad a = b + s c over arrays
// far larger than the caches. Prints one JSON line; each is the best of repeats.
//
//   build/tests/measure/measure_machine_peak [THREADS=2]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <immintrin.h>

namespace {

constexpr long kIterations = 20'000'000;
constexpr int kChains = 10;  // more independent FMAs than the latency x ports (4 x 2) hides

__attribute__((target("avx512f"))) float fmaAvx512(float seed) {
  __m512 acc[kChains];
  const __m512 m = _mm512_set1_ps(0.999999f), a = _mm512_set1_ps(1e-7f);
  for (int c = 0; c < kChains; ++c) acc[c] = _mm512_set1_ps(seed + float(c));
  for (long i = 0; i < kIterations; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = _mm512_fmadd_ps(acc[c], m, a);
  alignas(64) float out[16];
  float sum = 0;
  for (int c = 0; c < kChains; ++c) {
    _mm512_store_ps(out, acc[c]);
    for (float x : out) sum += x;
  }
  return sum;
}

__attribute__((target("avx2,fma"))) float fmaAvx2(float seed) {
  __m256 acc[kChains];
  const __m256 m = _mm256_set1_ps(0.999999f), a = _mm256_set1_ps(1e-7f);
  for (int c = 0; c < kChains; ++c) acc[c] = _mm256_set1_ps(seed + float(c));
  for (long i = 0; i < kIterations; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = _mm256_fmadd_ps(acc[c], m, a);
  alignas(32) float out[8];
  float sum = 0;
  for (int c = 0; c < kChains; ++c) {
    _mm256_store_ps(out, acc[c]);
    for (float x : out) sum += x;
  }
  return sum;
}

float fmaScalar(float seed) {
  float acc[kChains];
  for (int c = 0; c < kChains; ++c) acc[c] = seed + float(c);
  for (long i = 0; i < kIterations; ++i)
    for (int c = 0; c < kChains; ++c) acc[c] = acc[c] * 0.999999f + 1e-7f;
  float sum = 0;
  for (float x : acc) sum += x;
  return sum;
}

template <typename Body>
double bestSeconds(int repeats, int threads, const Body& body) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back([&, t] { body(t); });
    for (auto& th : pool) th.join();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::max(1, std::atoi(argv[1])) : 2;
  __builtin_cpu_init();
  const char* isa = __builtin_cpu_supports("avx512f") ? "avx512"
                    : (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) ? "avx2" : "scalar";
  const int lanes = isa[3] == '5' ? 16 : isa[0] == 'a' ? 8 : 1;
  volatile float sink = 0;
  const double fmaSeconds = bestSeconds(3, threads, [&](int t) {
    const float s = isa[3] == '5' ? fmaAvx512(float(t)) : isa[0] == 'a' ? fmaAvx2(float(t)) : fmaScalar(float(t));
    sink = sink + s;
  });
  const double flops = 2.0 * lanes * kChains * double(kIterations) * threads;

  // STREAM triad: 3 arrays of 32 M floats (384 MB), split among the threads;
  // each thread first touches its own part.
  const size_t n = size_t(32) << 20;
  std::vector<float> a, b, c;
  a.resize(n), b.resize(n), c.resize(n);
  const auto part = [&](int t) {
    return std::pair{n * size_t(t) / size_t(threads), n * size_t(t + 1) / size_t(threads)};
  };
  bestSeconds(1, threads, [&](int t) {
    const auto [lo, hi] = part(t);
    for (size_t i = lo; i < hi; ++i) a[i] = 0.0f, b[i] = 1.0f, c[i] = 2.0f;
  });
  const float scalar = 3.0f;
  const double triadSeconds = bestSeconds(5, threads, [&](int t) {
    const auto [lo, hi] = part(t);
    float* __restrict pa = a.data();
    const float* __restrict pb = b.data();
    const float* __restrict pc = c.data();
    for (size_t i = lo; i < hi; ++i) pa[i] = pb[i] + scalar * pc[i];
  });
  sink = sink + a[n / 2];
  std::printf("{\"threads\": %d, \"isa\": \"%s\", \"fp32_gflops\": %.2f, \"triad_gb_per_s\": %.2f}\n", threads, isa,
              flops / fmaSeconds * 1e-9, 3.0 * sizeof(float) * double(n) / triadSeconds * 1e-9);
  return 0;
}
