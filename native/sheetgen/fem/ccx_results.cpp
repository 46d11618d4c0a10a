// The readers of a ccx .dat and the runner of write_ccx_deck's decks
// (ccx_export.hpp; docs/fem.md "CalculiX export").
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

// "displacements (vx,vy,vz) for set NALL and time  0.1000000E+01"
CcxDisplacementBlock block_header(const std::string& line) {
  CcxDisplacementBlock b;
  const auto set = line.find("for set ");
  if (set != std::string::npos) std::istringstream(line.substr(set + 8)) >> b.set;
  const auto time = line.find("and time");
  if (time != std::string::npos) std::istringstream(line.substr(time + 8)) >> b.time;
  return b;
}

// A row of one integer and `n` numbers, nothing else.
bool numeric_row(const std::string& line, int n, int& id, double* values) {
  std::istringstream s(line);
  if (!(s >> id)) return false;
  for (int k = 0; k < n; ++k)
    if (!(s >> values[k])) return false;
  s >> std::ws;
  return s.eof();
}

enum class Section { kNone, kDisplacements, kBuckling, kEigenvalues };

// Which block a line opens, if any.
Section section_opened_by(const std::string& line) {
  if (line.find("displacements (vx,vy,vz)") != std::string::npos) return Section::kDisplacements;
  if (line.find("B U C K L I N G   F A C T O R   O U T P U T") != std::string::npos) return Section::kBuckling;
  if (line.find("E I G E N V A L U E   O U T P U T") != std::string::npos) return Section::kEigenvalues;
  return Section::kNone;
}

// One sentence from ccx's log: its first *ERROR message (to the next blank
// line), else its last line, whitespace collapsed.
std::string log_sentence(const std::string& log) {
  std::string text;
  const auto err = log.find("*ERROR");
  if (err != std::string::npos) {
    const auto end = log.find("\n\n", err);
    text = log.substr(err, end == std::string::npos ? std::string::npos : end - err);
  } else {
    const auto last = log.find_last_not_of(" \t\r\n");
    const auto start = last == std::string::npos ? 0 : log.rfind('\n', last);
    text = last == std::string::npos ? "no output" : log.substr(start == std::string::npos ? 0 : start + 1);
  }
  std::string out;
  for (char c : text) {
    const bool space = c == ' ' || c == '\t' || c == '\r' || c == '\n';
    if (space && (out.empty() || out.back() == ' ')) continue;
    out += space ? ' ' : c;
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out.size() > 300 ? out.substr(0, 300) + "..." : out;
}

// Runs `ccx -i job` in work_dir; returns its wall time, s.
double run_ccx(const std::string& work_dir, const std::string& job, const std::string& ccx) {
  std::remove((work_dir + "/" + job + ".dat").c_str());
  const std::string cmd = "cd '" + work_dir + "' && '" + ccx + "' -i '" + job + "' > '" + job + ".log' 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ifstream log(work_dir + "/" + job + ".log");
  std::stringstream log_text;
  log_text << log.rdbuf();
  if (rc != 0 || log_text.str().find("*ERROR") != std::string::npos)
    throw FemError("ccx", "`" + ccx + " -i " + job + "` in " + work_dir + " failed (status " + std::to_string(rc) +
                              "): " + log_sentence(log_text.str()));
  return seconds;
}

// One case from its ccx displacements: translations of every written node,
// rotations of rigid-link masters (their ROT NODE), f^T u and the deflection.
CcxCaseSolution case_solution(const ShellModel& m, const CcxDeckMap& map, const ShellLoadCase& c,
                              const std::map<int, Vec3>& u) {
  auto at = [&u](int id) {
    auto it = u.find(id);
    return it == u.end() ? Vec3(Vec3::Zero()) : it->second;
  };
  CcxCaseSolution sol;
  sol.name = c.name;
  sol.displacements.assign(m.nodes.size(), Vector6d::Zero());
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (map.node_id[i] > 0) sol.displacements[i].head<3>() = at(map.node_id[i]);
  std::vector<char> has_rotation(m.nodes.size(), 0);
  for (size_t l = 0; l < m.rigid_links.size(); ++l) {
    const int master = m.rigid_links[l].master;
    sol.displacements[master].head<3>() = at(map.ref_node[l]);
    sol.displacements[master].tail<3>() = at(map.rot_node[l]);
    has_rotation[master] = 1;
  }
  int load_node = m.load_node;
  double best = -1;
  for (const NodalLoad& f : c.loads) {
    sol.compliance += f.force.dot(sol.displacements[f.node].head<3>());
    if (f.moment.squaredNorm() > 0) {
      if (has_rotation[f.node]) sol.compliance += f.moment.dot(sol.displacements[f.node].tail<3>());
      else sol.compliance_complete = false;
    }
    if (m.load_node < 0 && sol.displacements[f.node].head<3>().norm() > best) {
      best = sol.displacements[f.node].head<3>().norm();
      load_node = f.node;
    }
  }
  if (load_node >= 0) sol.load_deflection = sol.displacements[load_node].head<3>().norm();
  return sol;
}

}  // namespace

CcxDatResults read_ccx_dat(const std::string& dat_path) {
  std::ifstream f(dat_path);
  if (!f) throw FemError("ccx results", "cannot read " + dat_path);
  CcxDatResults r;
  Section section = Section::kNone;
  int rows = 0;  // data rows of the open section; a line that is none ends it after the first
  std::string line;
  while (std::getline(f, line)) {
    const Section opened = section_opened_by(line);
    if (opened != Section::kNone) {
      section = opened;
      rows = 0;
      if (opened == Section::kDisplacements) r.displacements.push_back(block_header(line));
      continue;
    }
    if (section == Section::kNone || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    int id = 0;
    double v[4];
    bool row = false;
    if (section == Section::kDisplacements && (row = numeric_row(line, 3, id, v)))
      r.displacements.back().u[id] = Vec3(v[0], v[1], v[2]);
    else if (section == Section::kBuckling && (row = numeric_row(line, 1, id, v)))
      r.buckling_factors.push_back(v[0]);
    else if (section == Section::kEigenvalues && (row = numeric_row(line, 4, id, v)))
      r.frequencies_hz.push_back(v[2]);  // eigenvalue, omega (rad/time), f (cycles/time), imaginary part
    if (row) ++rows;
    else if (rows > 0) section = Section::kNone;  // headers come before the rows, the next block after them
  }
  return r;
}

std::map<int, Vec3> read_ccx_displacements(const std::string& dat_path) {
  const CcxDatResults r = read_ccx_dat(dat_path);
  for (auto it = r.displacements.rbegin(); it != r.displacements.rend(); ++it)
    if (!it->u.empty()) return it->u;
  throw FemError("ccx results", dat_path + " holds no displacement block");
}

CcxEnvelope solve_envelope_with_ccx(const ShellModel& m, const std::string& work_dir, const std::string& job,
                                    const std::string& ccx, const CcxExportOptions& options) {
  const CcxDeckMap map = write_ccx_deck(m, work_dir + "/" + job + ".inp", options);
  CcxEnvelope env;
  env.wall_seconds = run_ccx(work_dir, job, ccx);
  const std::string dat = work_dir + "/" + job + ".dat";
  const CcxDatResults r = read_ccx_dat(dat);
  // The static steps print set NALL; the eigenvalue steps before them print none.
  std::vector<const CcxDisplacementBlock*> statics;
  for (const CcxDisplacementBlock& b : r.displacements)
    if (b.set == "NALL") statics.push_back(&b);
  const std::vector<ShellLoadCase> cases = m.cases();
  if (statics.size() != cases.size())
    throw FemError("ccx results", dat + " holds " + std::to_string(statics.size()) +
                                      " displacement blocks of set NALL where the deck has " +
                                      std::to_string(cases.size()) + " static cases");
  for (size_t c = 0; c < cases.size(); ++c) env.cases.push_back(case_solution(m, map, cases[c], statics[c]->u));
  if (options.buckle_case >= 0 && r.buckling_factors.empty())
    throw FemError("ccx results", dat + " holds no buckling factor although the deck has a *BUCKLE step");
  env.buckling_factors = r.buckling_factors;
  if (static_cast<int>(r.frequencies_hz.size()) < options.frequency_modes)
    throw FemError("ccx results", dat + " holds " + std::to_string(r.frequencies_hz.size()) +
                                      " eigenfrequencies where the deck asks for " +
                                      std::to_string(options.frequency_modes));
  env.frequencies_hz = r.frequencies_hz;
  return env;
}

CcxSolution solve_with_ccx(const ShellModel& m, const std::string& work_dir, const std::string& job,
                           const std::string& ccx, const CcxExportOptions& options) {
  const CcxEnvelope env = solve_envelope_with_ccx(m, work_dir, job, ccx, options);
  const CcxCaseSolution& first = env.cases.front();
  CcxSolution sol;
  sol.displacements = first.displacements;
  sol.compliance = first.compliance;
  sol.compliance_complete = first.compliance_complete;
  sol.load_deflection = first.load_deflection;
  sol.wall_seconds = env.wall_seconds;
  return sol;
}

}  // namespace sheetgen
