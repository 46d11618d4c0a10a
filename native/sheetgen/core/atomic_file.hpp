#pragma once
// A file written under a temporary name beside its target and renamed over the
// target only once it is complete: a reader never sees half a file, and a
// failed write leaves nothing behind. The
// temporary name is `<path>.tmp-<pid>-<n>`, in the same folder so that the
// rename stays on one file system.
#include <string>

namespace sheetgen {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();  // removes the temporary file unless commit() moved it
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return temp_; }
  // Renames the temporary file over the target. Returns "" on success, else
  // the reason it failed (the temporary file is then removed).
  std::string commit();

 private:
  std::string path_, temp_;
  bool committed_ = false;
};

}  // namespace sheetgen
