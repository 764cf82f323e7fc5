#include "program_binary_cache.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <utility>

#include "file_bytes.h"

namespace gridrt {

namespace {

namespace fs = std::filesystem;

constexpr char kMagic[] = "gridrt program binary 1\n";

// FNV-1a, 64 bits: stable across builds and runs, unlike std::hash.
uint64_t fnv1a(const unsigned char* bytes, size_t count) {
  uint64_t h = 14695981039346656037ull;
  for (size_t k = 0; k < count; ++k) h = (h ^ bytes[k]) * 1099511628211ull;
  return h;
}

uint64_t fnv1a(const std::string& text) {
  return fnv1a(reinterpret_cast<const unsigned char*>(text.data()), text.size());
}

std::string header(const std::string& key) {
  return kMagic + std::to_string(key.size()) + "\n" + key;
}

}  // namespace

std::string ProgramBinaryCache::defaultDir() {
  if (const char* dir = std::getenv("GRIDRT_CACHE_DIR")) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::string(xdg) + "/gridrt";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::string(home) + "/.cache/gridrt";
  return "";
}

std::string ProgramBinaryCache::pathOf(const std::string& key) const {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin", (unsigned long long)fnv1a(key));
  return dir_ + "/" + name;
}

std::optional<std::vector<unsigned char>> ProgramBinaryCache::load(const std::string& key) const {
  if (dir_.empty()) return std::nullopt;
  const std::string path = pathOf(key);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  const std::string expected = header(key);
  std::string found(expected.size(), '\0');
  if (!in.read(found.data(), std::streamsize(found.size())) || found != expected)
    return std::nullopt;
  // The binary's length and checksum: a damaged binary can crash a driver (PoCL 3.1
  // segfaults on one), so it must never reach it.
  unsigned long long length = 0, checksum = 0;
  char newline = 0;
  if (!(in >> length >> checksum) || !in.get(newline) || newline != '\n' || length == 0)
    return std::nullopt;
  std::vector<unsigned char> binary;
  if (!readStreamBytes(in, binary) || binary.size() != length ||
      fnv1a(binary.data(), binary.size()) != checksum)
    return std::nullopt;
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // used now
  return binary;
}

void ProgramBinaryCache::store(const std::string& key,
                               const std::vector<unsigned char>& binary) const {
  if (dir_.empty() || binary.empty()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  const std::string path = pathOf(key);
  const std::string temp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    const std::string head = header(key) + std::to_string(binary.size()) + " " +
                             std::to_string(fnv1a(binary.data(), binary.size())) + "\n";
    out.write(head.data(), std::streamsize(head.size()));
    out.write(reinterpret_cast<const char*>(binary.data()), std::streamsize(binary.size()));
    if (!out) {
      out.close();
      fs::remove(temp, ec);
      return;
    }
  }
  fs::rename(temp, path, ec);
  if (ec) fs::remove(temp, ec);
  prune();
}

void ProgramBinaryCache::prune() const {
  std::vector<std::pair<fs::file_time_type, fs::path>> entries;
  std::error_code ec;
  try {  // a directory listing that fails half way (it can throw) just ends the pruning
    const fs::file_time_type stale = fs::file_time_type::clock::now() - std::chrono::hours(1);
    for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) {
      const fs::file_time_type used = e.last_write_time(ec);
      if (ec) continue;
      if (e.path().extension() == ".bin")
        entries.emplace_back(used, e.path());
      else if (e.path().filename().string().find(".bin.tmp") != std::string::npos && used < stale)
        fs::remove(e.path(), ec);  // left by a process that died while writing it
    }
  } catch (const fs::filesystem_error&) {
    return;
  }
  if (entries.size() <= kMaxEntries) return;
  std::sort(entries.begin(), entries.end(), std::greater<>());  // the newest first
  for (size_t k = kMaxEntries; k < entries.size(); ++k) fs::remove(entries[k].second, ec);
}

}  // namespace gridrt
