#pragma once
// The one exception type for bad user input. Its message is one sentence that
// names the file, the field and what is wrong, ready for the CLI and the add-on.
#include <stdexcept>
#include <string>

namespace sheetgen {

class InputError : public std::runtime_error {
 public:
  // file: the file the user gave (or "<inline>"); field: a JSON path such as
  // "loads[2].force" or a location such as "line 14"; problem: what is wrong.
  InputError(const std::string& file, const std::string& field, const std::string& problem);

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_, field_, problem_;
};

}  // namespace sheetgen
