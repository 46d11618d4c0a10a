#pragma once
// Typed, path-aware access to a JSON document: every failure throws an
// InputError naming the file and the JSON path ("loads[2].force").
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// Prefix of the strings that stand for NaN/Infinity tokens in a problem file.
inline constexpr const char* kNonFiniteMarker = "@sheetgen-non-finite:";

class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, std::string file, std::string path)
      : value_(&value), file_(std::move(file)), path_(std::move(path)) {}

  const nlohmann::json& raw() const { return *value_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

  bool has(const std::string& key) const;
  JsonNode at(const std::string& key) const;  // required member of an object
  std::optional<JsonNode> find(const std::string& key) const;
  JsonNode at(size_t index) const;            // element of an array
  size_t size() const;                        // array length (throws unless an array)

  void expect_object() const;
  void expect_array() const;
  std::string as_string() const;
  double as_number() const;                   // finite
  double as_positive() const;                 // finite and > 0
  double as_non_negative() const;             // finite and >= 0
  long long as_integer() const;
  Vec3 as_vec3() const;                       // array of 3 finite numbers

  // Optional member with a default; present members are validated like at(key).
  double number_or(const std::string& key, double fallback) const;
  double positive_or(const std::string& key, double fallback) const;
  double non_negative_or(const std::string& key, double fallback) const;
  long long integer_or(const std::string& key, long long fallback) const;

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  std::string type_name() const;
  const nlohmann::json* value_;
  std::string file_;
  std::string path_;
};

// Fails naming the first member of the object `node` that is not in `allowed`
// (a misspelt field must not silently become a default).
void reject_unknown(const JsonNode& node, std::initializer_list<const char*> allowed);

// parent["name"]: a non-empty string, one path component (names become output
// folder names), not yet in `seen` (then added); `what` names the kind in errors.
std::string checked_name(const JsonNode& parent, std::set<std::string>& seen, const char* what);

}  // namespace sheetgen
