#include "sheetgen/core/input_error.hpp"

namespace sheetgen {

static std::string compose(const std::string& file, const std::string& field, const std::string& problem) {
  std::string msg = file;
  if (!field.empty()) msg += ": " + field;
  msg += ": " + problem;
  if (!msg.empty() && msg.back() != '.') msg += '.';
  return msg;
}

InputError::InputError(const std::string& file, const std::string& field, const std::string& problem)
    : std::runtime_error(compose(file, field, problem)), file_(file), field_(field), problem_(problem) {}

}  // namespace sheetgen
