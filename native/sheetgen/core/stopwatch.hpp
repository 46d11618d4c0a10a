#pragma once
// Wall and CPU time of a stretch of work. The CPU time is the whole process's
// (every thread), so over a stage that runs alone it is that stage's, and CPU
// over wall says how many cores the stage kept busy (docs/benchmarks.md "Cores
// busy, stage by stage").
#include <chrono>

namespace sheetgen {

struct Elapsed {
  double wall_seconds = 0;  // s, steady clock
  double cpu_seconds = 0;   // s, the process's CPU time (user + system, every thread)
  Elapsed& operator+=(const Elapsed& other) {
    wall_seconds += other.wall_seconds;
    cpu_seconds += other.cpu_seconds;
    return *this;
  }
};

class Stopwatch {
 public:
  Stopwatch();  // starts now
  Elapsed elapsed() const;
  double wall_seconds() const;

 private:
  std::chrono::steady_clock::time_point wall_start_;
  double cpu_start_;  // s
};

// The process's CPU time so far, s.
double process_cpu_seconds();

}  // namespace sheetgen
