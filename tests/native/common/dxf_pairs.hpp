#pragma once
// A DXF text as its (group code, value) pairs, for tests that look at the entities.
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace sheetgen::fixtures {

inline std::vector<std::pair<int, std::string>> dxf_pairs(const std::string& dxf) {
  std::istringstream in(dxf);
  std::vector<std::pair<int, std::string>> out;
  std::string code, value;
  while (std::getline(in, code) && std::getline(in, value)) out.emplace_back(std::stoi(code), value);
  return out;
}

}  // namespace sheetgen::fixtures
