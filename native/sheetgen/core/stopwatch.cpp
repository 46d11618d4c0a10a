#include "sheetgen/core/stopwatch.hpp"

#include <ctime>

namespace sheetgen {

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

Stopwatch::Stopwatch() : wall_start_(std::chrono::steady_clock::now()), cpu_start_(process_cpu_seconds()) {}

double Stopwatch::wall_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
}

Elapsed Stopwatch::elapsed() const { return {wall_seconds(), process_cpu_seconds() - cpu_start_}; }

}  // namespace sheetgen
