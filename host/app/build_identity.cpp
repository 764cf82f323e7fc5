#include "build_identity.h"

#include <openssl/evp.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

namespace gridrt {

const char* embeddedKernelsDigest();  // generated with the kernel sources at build time

namespace {

constexpr size_t kReadChunkBytes = 1 << 20;

std::string hex(const unsigned char* bytes, unsigned length) {
  static const char digits[] = "0123456789abcdef";
  std::string out;
  for (unsigned k = 0; k < length; ++k) {
    out += digits[bytes[k] >> 4];
    out += digits[bytes[k] & 15];
  }
  return out;
}

// SHA-256 of the file's bytes in hex, or "unknown (why)".
std::string fileSha256(const char* path) {
  std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path, "rb"), &std::fclose);
  if (!file) return std::string("unknown (cannot read ") + path + ": " + std::strerror(errno) + ")";
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> context(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1)
    return "unknown (no SHA-256 in libcrypto)";
  std::vector<unsigned char> chunk(kReadChunkBytes);
  size_t got = 0;
  while ((got = std::fread(chunk.data(), 1, chunk.size(), file.get())) > 0)
    EVP_DigestUpdate(context.get(), chunk.data(), got);
  if (std::ferror(file.get())) return std::string("unknown (error reading ") + path + ")";
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned length = 0;
  EVP_DigestFinal_ex(context.get(), digest, &length);
  return hex(digest, length);
}

}  // namespace

std::string versionText(const std::string& version) {
  return "gridrt " + version + "\nbuild " + fileSha256("/proc/self/exe") + "\nkernels " +
         embeddedKernelsDigest();
}

}  // namespace gridrt
