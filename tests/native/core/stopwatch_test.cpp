// The stopwatch reads the process's CPU clock beside the wall clock: a thread
// that sleeps uses wall time and no CPU, one that computes uses both, and one
// thread cannot use more CPU than the wall time that passed.
#include "sheetgen/core/stopwatch.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

namespace sheetgen {
namespace {

TEST(Stopwatch, SleepingTakesWallTimeAndNoCpu) {
  const Stopwatch clock;
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const Elapsed e = clock.elapsed();
  EXPECT_GE(e.wall_seconds, 0.1);
  // The test's process does nothing else while it sleeps; what CPU it shows
  // is the clock calls themselves.
  EXPECT_LT(e.cpu_seconds, 0.5 * e.wall_seconds);
}

TEST(Stopwatch, OneComputingThreadUsesAtMostTheWallTime) {
  const Stopwatch clock;
  volatile double sink = 0;
  while (clock.wall_seconds() < 0.1)
    for (int i = 0; i < 1000; ++i) sink = sink + std::sqrt(static_cast<double>(i));
  const Elapsed e = clock.elapsed();
  EXPECT_GT(e.cpu_seconds, 0.0);
  // Read after the wall clock, the CPU clock may lead it by its resolution.
  EXPECT_LE(e.cpu_seconds, e.wall_seconds + 1e-3);
}

TEST(Stopwatch, ElapsedTimesAdd) {
  Elapsed a{1.5, 2.5};
  a += Elapsed{0.25, 0.5};
  EXPECT_DOUBLE_EQ(a.wall_seconds, 1.75);
  EXPECT_DOUBLE_EQ(a.cpu_seconds, 3.0);
}

}  // namespace
}  // namespace sheetgen
