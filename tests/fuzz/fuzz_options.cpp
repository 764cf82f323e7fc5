// libFuzzer target: the input is split into argv words (on NUL and ASCII whitespace) and
// parsed as a gridrt command line. Parsing may succeed, or refuse with UsageError; any
// other exception or crash is a finding. --help and --version print to std::cout, which is
// sent to a null stream so the fuzzer's own output stays readable.
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <streambuf>
#include <string>
#include <vector>

#include "errors.h"
#include "options.h"

namespace {

// A stream buffer that drops everything (no allocation per write).
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

bool isSeparator(uint8_t c) { return c == 0 || c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::vector<std::string> splitWords(const uint8_t* data, size_t size) {
  std::vector<std::string> words{"gridrt"};
  std::string word;
  for (size_t i = 0; i < size; ++i) {
    if (!isSeparator(data[i])) {
      word.push_back(char(data[i]));
    } else if (!word.empty()) {
      words.push_back(word);
      word.clear();
    }
  }
  if (!word.empty()) words.push_back(word);
  return words;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static NullBuffer null_buffer;
  static std::streambuf* const original = std::cout.rdbuf(&null_buffer);
  (void)original;
  std::vector<std::string> words = splitWords(data, size);
  std::vector<const char*> argv;
  for (const auto& w : words) argv.push_back(w.c_str());
  try {
    gridrt::parseCommandLine(int(argv.size()), argv.data());
  } catch (const gridrt::UsageError&) {
    // The documented way to refuse a bad command line.
  }
  return 0;
}
