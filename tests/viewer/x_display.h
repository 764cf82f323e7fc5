// An X server of the test's own (Xvfb) and the viewer in it, driven by xdotool, read back
// with xwd: what a user at the window does and sees, for the window tests.
#pragma once
#include <string>
#include <vector>

namespace gridrt::test {

// The programs the window tests need that the machine lacks ("Xvfb, xwd"), empty if none.
std::string missingXPrograms();

// Xvfb on a free display number, ended by the destructor.
class VirtualDisplay {
 public:
  VirtualDisplay();
  ~VirtualDisplay();
  VirtualDisplay(const VirtualDisplay&) = delete;
  VirtualDisplay& operator=(const VirtualDisplay&) = delete;
  bool started() const { return !name_.empty(); }
  const std::string& name() const { return name_; }  // ":N"
  const std::string& failure() const { return failure_; }

 private:
  int pid_ = -1;
  std::string name_, failure_;
};

// `gridrt --view ARGS` on `display` in folder `dir`, its standard output and error in files.
class ViewerProcess {
 public:
  ViewerProcess(const std::string& display, const std::string& dir,
                const std::vector<std::string>& args);
  ~ViewerProcess();  // kills it if it still runs
  ViewerProcess(const ViewerProcess&) = delete;
  ViewerProcess& operator=(const ViewerProcess&) = delete;

  // The window's X id once it is mapped and titled "gridrt...", "" after timeout_s.
  std::string waitForWindow(double timeout_s);
  // xdotool key KEYS... to the window, focused since waitForWindow (X key names: "Left",
  // "p", "5").
  void keys(const std::vector<std::string>& names);
  // Any xdotool command line against the display ("mousemove --window W 10 10 ...").
  int xdotool(const std::string& arguments);
  // The first `lines` lines of standard output, waiting up to timeout_s; fewer if it ends.
  std::vector<std::string> outputLines(size_t lines, double timeout_s);
  // The window's title once it contains `text`, "" after timeout_s.
  std::string waitForTitle(const std::string& text, double timeout_s);
  // Waits up to timeout_s for the process to end: its exit code, -1 if it did not.
  int waitForExit(double timeout_s);
  std::string errorOutput() const;

 private:
  std::string display_, dir_, window_, out_path_, err_path_;
  int pid_ = -1;
  bool ended_ = false;
  int exit_code_ = -1;
};

// An X window's pixels (xwd): 8-bit RGB, row 0 at the top; empty on failure.
struct Screenshot {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};
Screenshot screenshot(const std::string& display, const std::string& window);

// A PNG's or other image's 8-bit RGB codes, read through the image module.
Screenshot imageCodes(const std::string& path);

}  // namespace gridrt::test
