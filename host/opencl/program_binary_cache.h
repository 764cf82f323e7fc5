// Built OpenCL program binaries kept on disk between runs, so that a later process loads
// a program instead of compiling it. PoCL has a cache of its own, but to find an entry it
// preprocesses the source with clang first, a noticeable share of a short render for the
// two GridRT kernels; loading a binary is several times cheaper (docs/history.md).
//
// An entry is named by a hash of its key and holds the whole key (the kernel source, the
// build options, the platform's and device's names and versions) and the binary's length
// and checksum, all checked on load, so a collision, an entry from another driver or a
// damaged file is a miss, never a wrong program or a driver fed garbage. Entries are
// written to a temporary file and renamed into place (concurrent runs are safe).
// Nothing here is an error: a directory that cannot be made or written is a miss.
// The directory keeps the kMaxEntries entries used last (a load marks an entry used);
// every gridrt version and kernel variant adds its own, ~250 KB each.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace gridrt {

class ProgramBinaryCache {
 public:
  static constexpr size_t kMaxEntries = 64;

  // dir empty: no cache (every load misses, stores do nothing).
  explicit ProgramBinaryCache(std::string dir) : dir_(std::move(dir)) {}

  // $GRIDRT_CACHE_DIR, else $XDG_CACHE_HOME/gridrt, else $HOME/.cache/gridrt ("" if
  // none of them is set).
  static std::string defaultDir();

  const std::string& dir() const { return dir_; }
  std::optional<std::vector<unsigned char>> load(const std::string& key) const;
  void store(const std::string& key, const std::vector<unsigned char>& binary) const;
  // The file an entry for `key` lives in (tests).
  std::string pathOf(const std::string& key) const;

 private:
  // Removes all but the kMaxEntries entries used last, and temporary files older than an
  // hour (a process that died while writing one).
  void prune() const;
  std::string dir_;
};

}  // namespace gridrt
