#include "sheetgen/pipeline/load_environments.hpp"

#include "sheetgen/core/cancelled.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen {

LoadEnvironments::LoadEnvironments(const Problem& problem, GenerateProgress* progress)
    : problem_(problem), progress_(progress) {}

EnvironmentOptions LoadEnvironments::options() const {
  EnvironmentOptions eo;
  if (progress_) eo.cancel = &progress_->cancel;
  return eo;
}

const Environment* LoadEnvironments::next() {
  if (!current()) return nullptr;
  if (new_parts_.empty()) return env_.get();
  try {
    env_ = std::make_unique<Environment>(*env_, new_parts_, options());
  } catch (const Cancelled&) {
    return nullptr;
  }
  additions_.push_back(std::move(new_parts_));
  new_parts_.clear();
  return env_.get();
}

const Environment* LoadEnvironments::current() {
  if (!env_) env_ = at_sheet(problem_);
  return env_.get();
}

void LoadEnvironments::release() { env_.reset(); }

std::unique_ptr<Environment> LoadEnvironments::at_sheet(const Problem& sheet) const {
  try {
    auto env = std::make_unique<Environment>(sheet, options());
    for (const auto& parts : additions_) env = std::make_unique<Environment>(*env, parts, options());
    return env;
  } catch (const Cancelled&) {
    return nullptr;
  }
}

void LoadEnvironments::add_part(EnvironmentMesh part) { new_parts_.push_back(std::move(part)); }

}  // namespace sheetgen
