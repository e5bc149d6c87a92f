// Path tracer benchmarks (Google Benchmark), run by hand, never in ctest:
//   build/tests/bench/gi-bench-reference [--benchmark_filter=...]
// Rays per second on the built-in Cornell box at 256x256, and the time to reach a fixed noise
// level there (estimated from two independent half-sample images, so no converged image is needed).
#include "gi/preset/preset.h"
#include "gi/reference/path_tracer.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

namespace {

struct Fixture {
    gi::Scene scene = gi::makeBuiltinScene("cornell");
    gi::FrameSettings frame = gi::frameSettings(gi::Preset{}, scene, 256, 256);
    gi::PathTracer tracer{scene};
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

void BM_CornellRaysPerSecond(benchmark::State& state) {
    Fixture& f = fixture();
    gi::ReferenceSettings rs;
    int sample = 0;
    uint64_t raysBefore = f.tracer.raysTraced();
    for (auto _ : state) {
        std::vector<double> sum;
        f.tracer.trace(f.frame, rs, sample, 4, sum);
        sample += 4;
        benchmark::DoNotOptimize(sum.data());
    }
    uint64_t rays = f.tracer.raysTraced() - raysBefore;
    state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
    state.counters["paths/s"] = benchmark::Counter(double(sample) * 256 * 256, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CornellRaysPerSecond)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// Relative RMS noise of the mean of two independent images: half the RMS of their difference
// over the RMS of their mean (the noise of each half is sqrt(2) times that of the full mean).
double relativeNoise(const std::vector<double>& a, const std::vector<double>& b, int samplesEach) {
    double diff2 = 0, mean2 = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        double x = a[i] / samplesEach, y = b[i] / samplesEach;
        diff2 += (x - y) * (x - y);
        mean2 += 0.25 * (x + y) * (x + y);
    }
    return 0.5 * std::sqrt(diff2) / std::sqrt(mean2);
}

void BM_CornellTimeToNoiseLevel(benchmark::State& state) {
    Fixture& f = fixture();
    const double target = double(state.range(0)) / 1000.0;
    for (auto _ : state) {
        auto start = std::chrono::steady_clock::now();
        gi::ReferenceSettings a, b;
        a.seed = 1;
        b.seed = 2;
        std::vector<double> sumA, sumB;
        int spp = 0, pass = 1;
        double noise = 1.0;
        while (noise > target && spp < 4096) {
            f.tracer.trace(f.frame, a, spp, pass, sumA);
            f.tracer.trace(f.frame, b, spp, pass, sumB);
            spp += pass;
            pass = std::min(pass * 2, 32);
            noise = relativeNoise(sumA, sumB, spp);
        }
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        state.SetIterationTime(seconds);
        state.counters["spp"] = 2.0 * spp;
        state.counters["noise"] = noise;
    }
}
BENCHMARK(BM_CornellTimeToNoiseLevel)->Arg(20)->Arg(10)->UseManualTime()->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
