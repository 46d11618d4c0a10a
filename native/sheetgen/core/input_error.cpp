#include "sheetgen/core/input_error.hpp"

namespace sheetgen {

// The message is one line for the CLI's stderr and the add-on's report: control
// characters the user put in a name or key ("a\nb" in JSON) are shown escaped.
static std::string one_line(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (unsigned char c : s) {
    if (c >= 0x20 && c != 0x7f) {
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      static const char hex[] = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

static std::string compose(const std::string& file, const std::string& field, const std::string& problem) {
  std::string msg = one_line(file);
  if (!field.empty()) msg += ": " + one_line(field);
  msg += ": " + one_line(problem);
  if (!msg.empty() && msg.back() != '.') msg += '.';
  return msg;
}

InputError::InputError(const std::string& file, const std::string& field, const std::string& problem)
    : std::runtime_error(compose(file, field, problem)), file_(file), field_(field), problem_(problem) {}

}  // namespace sheetgen
