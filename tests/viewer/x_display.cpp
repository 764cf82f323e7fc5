#include "x_display.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "image_output.h"
#include "run_command.h"
#include "test_support.h"

extern char** environ;

namespace gridrt::test {

namespace {

bool onPath(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// Runs `command` through the shell with DISPLAY set, its standard output returned.
std::string shellOutput(const std::string& display, const std::string& command, int* rc = nullptr) {
  const std::string line = "DISPLAY=" + display + " " + command + " 2>/dev/null";
  FILE* pipe = popen(line.c_str(), "r");
  std::string out;
  if (!pipe) return out;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  const int status = pclose(pipe);
  if (rc) *rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

void pause(double seconds) {
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

uint32_t readCard32(const std::string& bytes, size_t offset) {
  // XWD headers are big-endian.
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + offset);
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
}

int lowestBit(uint32_t mask) {
  int shift = 0;
  while (mask && !(mask & 1u)) mask >>= 1, ++shift;
  return shift;
}

}  // namespace

std::string missingXPrograms() {
  std::string missing;
  for (const char* program : {"Xvfb", "xdotool", "xwd"})
    if (!onPath(program)) missing += (missing.empty() ? "" : ", ") + std::string(program);
  return missing;
}

VirtualDisplay::VirtualDisplay() {
  // -displayfd: Xvfb picks a free display number and writes it to the pipe once it is ready.
  int fds[2];
  if (pipe(fds) != 0) {
    failure_ = "pipe failed";
    return;
  }
  const std::string fd = std::to_string(fds[1]);
  // -noreset: without it Xvfb resets when its last client leaves (xdotool, between two
  // commands), and a viewer connecting then is refused. -ardelay: no key repeats itself
  // when xdotool, on a busy machine, is late to release it.
  std::vector<std::string> argv{"Xvfb",     "-displayfd", fd,      "-screen", "0",
                                "1024x768x24", "-noreset", "-ardelay", "600000", "-nolisten",
                                "tcp"};
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "Xvfb", &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (rc != 0) {
    close(fds[0]);
    failure_ = "Xvfb could not be started: " + std::string(std::strerror(rc));
    return;
  }
  pid_ = pid;
  std::string number;
  char c;
  while (read(fds[0], &c, 1) == 1 && c != '\n') number += c;
  close(fds[0]);
  if (number.empty()) {
    failure_ = "Xvfb exited without a display";
    return;
  }
  name_ = ":" + number;
}

VirtualDisplay::~VirtualDisplay() {
  if (pid_ > 0) {
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
  }
}

ViewerProcess::ViewerProcess(const std::string& display, const std::string& dir,
                             const std::vector<std::string>& args)
    : display_(display), dir_(dir) {
  static int counter = 0;
  const std::string base = tempPath("viewer" + std::to_string(counter++));
  out_path_ = base + ".out";
  err_path_ = base + ".err";
  std::vector<std::string> argv{gridrtBinary(), "--view"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (auto& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "DISPLAY=", 8) != 0) env.push_back(*e);
  env.push_back("DISPLAY=" + display);
  std::vector<char*> cenv;
  for (auto& e : env) cenv.push_back(e.data());
  cenv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(dir.c_str()) != 0) _exit(126);
    const int in = open("/dev/null", O_RDONLY);
    const int out = open(out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(in, 0), dup2(out, 1), dup2(err, 2);
    execve(cargs[0], cargs.data(), cenv.data());
    _exit(127);
  }
  pid_ = pid;
}

ViewerProcess::~ViewerProcess() {
  if (pid_ > 0 && !ended_) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
}

std::string ViewerProcess::waitForWindow(double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  while (secondsSince(start) < timeout_s) {
    std::istringstream ids(shellOutput(display_, "xdotool search --onlyvisible --name '^gridrt'"));
    if (ids >> window_) {
      // The keys go to the focused window as a keyboard's would (XTEST): focus it.
      shellOutput(display_, "xdotool windowfocus --sync " + window_);
      return window_;
    }
    if (waitForExit(0) >= 0) return "";
    pause(0.05);
  }
  return "";
}

void ViewerProcess::keys(const std::vector<std::string>& names) {
  std::string command = "xdotool key --delay 20";
  for (const auto& n : names) command += " " + n;
  shellOutput(display_, command);
}

int ViewerProcess::xdotool(const std::string& arguments) {
  int rc = -1;
  shellOutput(display_, "xdotool " + arguments, &rc);
  return rc;
}

std::vector<std::string> ViewerProcess::outputLines(size_t lines, double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    std::vector<std::string> got;
    std::istringstream in(readWholeFile(out_path_));
    std::string line;
    while (std::getline(in, line) && got.size() < lines)
      if (in) got.push_back(line);  // only whole lines
    if (got.size() >= lines || secondsSince(start) >= timeout_s || waitForExit(0) >= 0) return got;
    pause(0.05);
  }
}

std::string ViewerProcess::waitForTitle(const std::string& text, double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  while (secondsSince(start) < timeout_s) {
    const std::string title = trimmed(shellOutput(display_, "xdotool getwindowname " + window_));
    if (title.find(text) != std::string::npos) return title;
    pause(0.05);
  }
  return "";
}

int ViewerProcess::waitForExit(double timeout_s) {
  const auto start = std::chrono::steady_clock::now();
  while (!ended_) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      ended_ = true;
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      break;
    }
    if (secondsSince(start) >= timeout_s) return -1;
    pause(0.05);
  }
  return exit_code_;
}

std::string ViewerProcess::errorOutput() const { return readWholeFile(err_path_); }

Screenshot screenshot(const std::string& display, const std::string& window) {
  Screenshot shot;
  const std::string bytes = shellOutput(display, "xwd -silent -id " + window);
  if (bytes.size() < 100) return shot;
  const uint32_t header_size = readCard32(bytes, 0), format = readCard32(bytes, 8);
  const uint32_t width = readCard32(bytes, 16), height = readCard32(bytes, 20);
  const uint32_t byte_order = readCard32(bytes, 28), bits_per_pixel = readCard32(bytes, 44);
  const uint32_t bytes_per_line = readCard32(bytes, 48);
  const uint32_t masks[3] = {readCard32(bytes, 56), readCard32(bytes, 60), readCard32(bytes, 64)};
  const uint32_t colours = readCard32(bytes, 76);
  const size_t data = size_t(header_size) + size_t(colours) * 12;  // XWDColor: 12 bytes
  // ZPixmap, TrueColor 24-bit colour in 32-bit pixels: the only layout Xvfb -screen WxHx24 has.
  if (format != 2 || bits_per_pixel != 32 || bytes.size() < data + size_t(bytes_per_line) * height)
    return shot;
  shot.width = int(width);
  shot.height = int(height);
  shot.rgb.resize(size_t(width) * height * 3);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const auto* p =
          reinterpret_cast<const unsigned char*>(bytes.data() + data + y * bytes_per_line + 4 * x);
      const uint32_t v = byte_order == 0 ? uint32_t(p[0]) | uint32_t(p[1]) << 8 |
                                               uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24
                                         : uint32_t(p[3]) | uint32_t(p[2]) << 8 |
                                               uint32_t(p[1]) << 16 | uint32_t(p[0]) << 24;
      for (int c = 0; c < 3; ++c)
        shot.rgb[(size_t(y) * width + x) * 3 + c] =
            (unsigned char)((v & masks[c]) >> lowestBit(masks[c]));
    }
  return shot;
}

Screenshot imageCodes(const std::string& path) {
  const ImageData image = readImage(path);
  Screenshot codes{image.width, image.height, {}};
  codes.rgb.resize(size_t(image.width) * image.height * 3);
  for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
    for (int c = 0; c < 3; ++c)
      codes.rgb[3 * p + c] =
          (unsigned char)std::lround(image.pixels[p * image.channels + c] * 255.0f);
  return codes;
}

}  // namespace gridrt::test
