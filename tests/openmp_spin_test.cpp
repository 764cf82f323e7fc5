// gridrt restarts itself once with a short libgomp spin (host/openmp_spin.h), unless the
// user chose the spin or the wait policy. libgomp's OMP_DISPLAY_ENV shows what it runs with.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "openmp_spin.h"
#include "run_command.h"
#include "test_support.h"

namespace {

using gridrt::test::gridrtBinary;
using gridrt::test::runCommand;

int occurrences(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

gridrt::test::CommandResult runVersion(const std::vector<std::string>& environment) {
  std::vector<std::string> argv = {"env", "-u", "GOMP_SPINCOUNT", "-u", "OMP_WAIT_POLICY",
                                   "OMP_DISPLAY_ENV=verbose"};
  argv.insert(argv.end(), environment.begin(), environment.end());
  argv.push_back(gridrtBinary());
  argv.push_back("--version");
  return runCommand(argv);
}

const std::string kShortSpin = std::string("GOMP_SPINCOUNT = '") + gridrt::kOpenMpSpinCount + "'";

TEST(OpenMpSpin, RestartsOnceWithTheShortSpin) {
  auto r = runVersion({});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, kShortSpin), 1) << r.err;
  EXPECT_EQ(occurrences(r.out, "gridrt "), 1) << "the program ran once: " << r.out;
}

TEST(OpenMpSpin, KeepsTheUsersSpinCount) {
  auto r = runVersion({"GOMP_SPINCOUNT=5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "GOMP_SPINCOUNT = '5'"), 1) << r.err;
  EXPECT_EQ(occurrences(r.err, kShortSpin), 0) << r.err;
}

TEST(OpenMpSpin, KeepsTheUsersWaitPolicy) {
  auto r = runVersion({"OMP_WAIT_POLICY=active"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(occurrences(r.err, "OMP_WAIT_POLICY = 'ACTIVE'"), 1) << r.err;
  EXPECT_EQ(occurrences(r.err, kShortSpin), 0) << r.err;
}

}  // namespace
