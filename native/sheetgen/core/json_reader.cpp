#include "sheetgen/core/json_reader.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>

#include "sheetgen/core/input_error.hpp"

namespace sheetgen {

namespace {
std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
}  // namespace

void JsonNode::fail(const std::string& problem) const { throw InputError(file_, path_.empty() ? "(top level)" : path_, problem); }

std::string JsonNode::type_name() const {
  const auto& v = *value_;
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  return "an object";
}

void JsonNode::expect_object() const {
  if (!value_->is_object()) fail("expected an object, got " + type_name());
}
void JsonNode::expect_array() const {
  if (!value_->is_array()) fail("expected an array, got " + type_name());
}

bool JsonNode::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

JsonNode JsonNode::at(const std::string& key) const {
  expect_object();
  auto it = value_->find(key);
  if (it == value_->end()) throw InputError(file_, join(path_, key), "required field is missing");
  return JsonNode(*it, file_, join(path_, key));
}

std::optional<JsonNode> JsonNode::find(const std::string& key) const {
  expect_object();
  auto it = value_->find(key);
  if (it == value_->end() || it->is_null()) return std::nullopt;
  return JsonNode(*it, file_, join(path_, key));
}

JsonNode JsonNode::at(size_t index) const {
  expect_array();
  if (index >= value_->size()) fail("index " + std::to_string(index) + " is out of range");
  return JsonNode((*value_)[index], file_, path_ + "[" + std::to_string(index) + "]");
}

size_t JsonNode::size() const {
  expect_array();
  return value_->size();
}

std::string JsonNode::as_string() const {
  if (!value_->is_string()) fail("expected a string, got " + type_name());
  return value_->get<std::string>();
}

double JsonNode::as_number() const {
  // NaN/Infinity tokens arrive as marked strings (problem.cpp); a literal such
  // as 1e999 is already refused by the parser (number overflow). Both are
  // "not a finite number"; the isfinite check below is the last line of defence.
  if (value_->is_string()) {
    const std::string& str = value_->get_ref<const std::string&>();
    if (str.rfind(kNonFiniteMarker, 0) == 0) fail("expected a finite number, got " + str.substr(std::strlen(kNonFiniteMarker)));
  }
  if (!value_->is_number()) fail("expected a number, got " + type_name());
  double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number, got " + std::to_string(v));
  return v;
}

double JsonNode::as_positive() const {
  double v = as_number();
  if (!(v > 0)) fail("must be greater than zero, got " + value_->dump());
  return v;
}

double JsonNode::as_non_negative() const {
  double v = as_number();
  if (v < 0) fail("must not be negative, got " + value_->dump());
  return v;
}

long long JsonNode::as_integer() const {
  if (!value_->is_number_integer()) fail("expected an integer, got " + (value_->is_number() ? value_->dump() : type_name()));
  // 2^63 and above are stored unsigned: converting would wrap to a negative index.
  if (value_->is_number_unsigned() && value_->get<unsigned long long>() > static_cast<unsigned long long>(LLONG_MAX))
    fail("integer " + value_->dump() + " is too large");
  return value_->get<long long>();
}

Vec3 JsonNode::as_vec3() const {
  if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers, got " + (value_->is_array() ? "an array of " + std::to_string(value_->size()) : type_name()));
  Vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = at(k).as_number();
  return v;
}

double JsonNode::number_or(const std::string& key, double fallback) const {
  auto n = find(key);
  return n ? n->as_number() : fallback;
}
double JsonNode::positive_or(const std::string& key, double fallback) const {
  auto n = find(key);
  return n ? n->as_positive() : fallback;
}
double JsonNode::non_negative_or(const std::string& key, double fallback) const {
  auto n = find(key);
  return n ? n->as_non_negative() : fallback;
}
long long JsonNode::integer_or(const std::string& key, long long fallback) const {
  auto n = find(key);
  return n ? n->as_integer() : fallback;
}

void reject_unknown(const JsonNode& node, std::initializer_list<const char*> allowed) {
  for (auto it = node.raw().begin(); it != node.raw().end(); ++it) {
    const std::string& key = it.key();
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return key == a; })) {
      std::string list;
      for (const char* a : allowed) list += std::string(list.empty() ? "" : ", ") + a;
      node.fail("unknown field '" + key + "' (expected one of: " + list + ")");
    }
  }
}

std::string checked_name(const JsonNode& parent, std::set<std::string>& seen, const char* what) {
  const JsonNode n = parent.at("name");
  std::string name = n.as_string();
  if (name.empty()) n.fail("name must not be empty");
  // Names become output folder names: keep them to one path component.
  if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos || name == "." || name == ".." ||
      name.find('\0') != std::string::npos)
    n.fail("name '" + name + "' must not contain '/' or '\\' or be '.' or '..'");
  if (!seen.insert(name).second) n.fail(std::string("duplicate ") + what + " name '" + name + "'");
  return name;
}

}  // namespace sheetgen
