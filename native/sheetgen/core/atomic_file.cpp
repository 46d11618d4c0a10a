#include "sheetgen/core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <filesystem>

namespace sheetgen {

namespace fs = std::filesystem;

namespace {
// Per process: two writers of one path in one process (threads) get two names.
std::atomic<unsigned> next_number{0};
}  // namespace

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)),
      temp_(path_ + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(next_number++)) {}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  std::error_code ec;
  fs::remove(fs::u8path(temp_), ec);
}

std::string AtomicFile::commit() {
  std::error_code ec;
  fs::rename(fs::u8path(temp_), fs::u8path(path_), ec);
  if (!ec) {
    committed_ = true;
    return "";
  }
  const std::string why = ec.message();
  fs::remove(fs::u8path(temp_), ec);
  return why;
}

}  // namespace sheetgen
