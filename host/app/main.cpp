// gridrt: parse the command line, run, and turn every error into one line and an exit
// code (2 usage, 1 anything else).
#include <CL/opencl.hpp>
#include <exception>
#include <iostream>
#include <new>

#include "application.h"
#include "cl_runtime.h"
#include "errors.h"
#include "interactive_viewer.h"
#include "options.h"

int main(int argc, char** argv) {
  try {
    auto options = gridrt::parseCommandLine(argc, argv);
    if (!options) return 0;
    if (options->view) return gridrt::runViewer(*options);
    return gridrt::runApplication(*options);
  } catch (const gridrt::UsageError& e) {
    std::cerr << "gridrt: " << e.what() << '\n';
    return 2;
  } catch (const cl::Error& e) {
    std::cerr << "gridrt: OpenCL error in " << e.what() << ": " << gridrt::clErrorName(e.err())
              << '\n';
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "gridrt: out of host memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "gridrt: " << e.what() << '\n';
    return 1;
  }
}
