#include "mapped_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "file_bytes.h"

#if defined(__linux__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace gridrt {

MappedFile::~MappedFile() { release(); }

void MappedFile::release() {
#if defined(__linux__)
  if (mapping_) munmap(const_cast<unsigned char*>(mapping_), mapping_size_);
#endif
  mapping_ = nullptr;
  mapping_size_ = 0;
  bytes_.clear();
}

bool MappedFile::open(const std::string& path, std::string& error) {
  release();
#if defined(__linux__)
  // Only a regular file is opened here: a FIFO opened and closed before being read again
  // would leave its writer without a reader for a moment (a broken pipe).
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && info.st_size > 0) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      error = std::strerror(errno);
      return false;
    }
    // The size of the file opened (it may have changed since the stat above).
    if (fstat(fd, &info) == 0 && info.st_size > 0) {
      void* at = mmap(nullptr, size_t(info.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (at != MAP_FAILED) {
        mapping_ = static_cast<const unsigned char*>(at);
        mapping_size_ = size_t(info.st_size);
      }
    }
    ::close(fd);
    if (mapping_) return true;
  }
#endif
  // Not a regular file, empty, or not mappable: read.
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = std::strerror(errno);
    return false;
  }
  if (!readStreamBytes(in, bytes_)) {
    error = "read error";
    return false;
  }
  return true;
}

}  // namespace gridrt
