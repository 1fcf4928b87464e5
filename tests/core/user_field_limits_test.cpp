// What a user's program may cost the service: no recursion proportional to its length (the longest chains compile
// on a 256 KiB stack), a compile that a cancelled request stops, and the workspace of an evaluation as the program
// reports it (checked against the memory it really takes) within a per-request budget (413 naming g).
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "core/basins.hpp"
#include "core/cancellation.hpp"
#include "core/groups/mechanics_groups.hpp"
#include "core/groups/son_group.hpp"
#include "core/request_error.hpp"
#include "core/sweep.hpp"
#include "core/user_field/program.hpp"
#include "core/user_field/user_vector_field.hpp"
#include "core/work_precision.hpp"
#include "core/parallel_for.hpp"

namespace lienewton {
namespace {

// Runs f on a thread with a stack of `bytes` (a deeper recursion than that would crash the test binary).
void on_small_stack(std::size_t bytes, const std::function<void()>& f) {
  pthread_attr_t attr;
  ASSERT_EQ(pthread_attr_init(&attr), 0);
  ASSERT_EQ(pthread_attr_setstacksize(&attr, bytes), 0);
  pthread_t thread;
  auto run = [](void* p) -> void* {
    (*static_cast<const std::function<void()>*>(p))();
    return nullptr;
  };
  ASSERT_EQ(pthread_create(&thread, &attr, run, const_cast<std::function<void()>*>(&f)), 0);
  pthread_join(thread, nullptr);
  pthread_attr_destroy(&attr);
}

TEST(UserFieldLimits, LongChainsCompileAndRunOnA256KiBStack) {
  std::string transposes = "g = (y - y')";  // 9 990 pairs of transposes: g = y - y'
  for (int i = 0; i < 9990; ++i) transposes += "''";
  std::string sum = "g = (y - y')*(0";  // 9 000 terms, left-associative
  for (int i = 0; i < 9000; ++i) sum += "+1";
  sum += ")";
  std::string products = "a = y";
  for (int i = 0; i < 6000; ++i) products += (i % 2 ? "*y" : ".*y'");
  products += "; g = a - a'";
  for (const std::string* source : {&transposes, &sum, &products}) {
    SCOPED_TRACE(source->substr(0, 40));
    bool compiled = false;
    Eigen::MatrixXd g;
    const Eigen::MatrixXd y = SONGroup(3).random(4);
    on_small_stack(256 * 1024, [&] {
      const auto program = user_field::compile(*source, 3, {});
      program->eval(y, 0.0, g);
      compiled = true;
    });
    ASSERT_TRUE(compiled);
    if (source == &transposes) {
      EXPECT_EQ(g, y - y.transpose());
    } else if (source == &sum) {
      EXPECT_EQ(g, 9000 * (y - y.transpose()));
    }
  }
}

TEST(UserFieldLimits, TheDeepestNestingTheParserAllowsCompilesOnA1MiBStack) {
  // 64 calls deep reaches the nesting limit; one more level is refused with a position.
  std::string deep = "y";
  for (int i = 0; i < 63; ++i) deep = "sin(" + deep + ")";
  bool compiled = false;
  std::string refused;
  on_small_stack(1024 * 1024, [&] {
    user_field::compile("a = " + deep + "; g = a - a'", 3, {});
    compiled = true;
    try {
      user_field::compile("a = sin(" + deep + "); g = a - a'", 3, {});
    } catch (const RequestError& e) {
      refused = e.what();
    }
  });
  EXPECT_TRUE(compiled);
  EXPECT_NE(refused.find("nests too deeply"), std::string::npos) << refused;
  // Brackets count 3 (the bracket, its element, the element's sign): 42 deep is the documented most.
  std::string brackets = "y";
  for (int i = 0; i < 42; ++i) brackets = "[" + brackets + "]";
  compiled = false;
  refused.clear();
  on_small_stack(1024 * 1024, [&] {
    user_field::compile("a = " + brackets + "; g = a - a'", 3, {});
    compiled = true;
    try {
      user_field::compile("a = [" + brackets + "]; g = a - a'", 3, {});
    } catch (const RequestError& e) {
      refused = e.what();
    }
  });
  EXPECT_TRUE(compiled);
  EXPECT_NE(refused.find("nests too deeply"), std::string::npos) << refused;
}

TEST(UserFieldLimits, ACancelledRequestStopsItsCompile) {
  // Folding these products is most of the compile's work: a cancelled token stops it at the next instruction.
  const std::string heavy = "a = ones(300); b = a*a; c = b*b; d = c*c; e = d*d; g = (y - y')*trace(e)";
  const CancellationToken passed(CancellationToken::Clock::now(), nullptr, nullptr);
  const CancellationScope scope(&passed);
  EXPECT_THROW(user_field::compile(heavy, 3, {}), Cancelled);
  const CancellationScope none(nullptr);
  EXPECT_NO_THROW(user_field::compile(heavy, 3, {}));
}

// The growth of the peak resident set while f runs in a child process (fresh pages: a large matrix is mapped anew).
double peak_growth_bytes(const std::function<void()>& f) {
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0) return -1;
  const pid_t child = fork();
  if (child == 0) {
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    f();
    getrusage(RUSAGE_SELF, &after);
    const double grown = double(after.ru_maxrss - before.ru_maxrss) * 1024.0;
    const ssize_t written = write(pipe_fds[1], &grown, sizeof grown);
    _exit(written == sizeof grown ? 0 : 1);
  }
  close(pipe_fds[1]);
  double grown = -1;
  if (read(pipe_fds[0], &grown, sizeof grown) != sizeof grown) grown = -1;
  close(pipe_fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return grown;
}

TEST(UserFieldLimits, ADerivativeOnBodiesHoldsWhatTheProgramReports) {
  // dg_y's matrix on 32 bodies takes its 384 directions a pass at a time: its peak is the program's reported
  // workspace (to a factor of 2), not the stack of every direction's 352 x 352 matrix (380 MB).
  constexpr int k = 32;
  const SE3xR6PowerGroup group(k);
  const auto program = user_field::compile("g = 0*y", 11 * k, {});
  const UserVectorField<SE3xR6PowerGroup> field(group, program);
  const SE3xR6PowerGroup::Element y = group.random(3);
  const double reported = program->workspace_bytes(group.dim());
  const double stacked = double(group.dim()) * (11.0 * k) * (11.0 * k) * sizeof(double);
  EXPECT_LT(reported, stacked / 10);
  const double measured = peak_growth_bytes([&] { (void)field.dg_matrix(group, y); });
  ASSERT_GT(measured, 0);
  EXPECT_GT(measured, reported / 4) << "reported " << reported << ", measured " << measured;
#if !defined(LIENEWTON_SANITIZED)
  EXPECT_LT(measured, reported * 2) << "reported " << reported << ", measured " << measured;
#endif
}

TEST(UserFieldLimits, WorkspaceIsWhatTheProgramReports) {
  // Values and tangents of 500x500 tilings of y, sin's derivative, dg_y's three stacked directions.
  const std::string source = "a = y(ones(1,500), ones(1,500)); b = sin(a) .* a; g = (y - y')*trace(b)";
  const auto program = user_field::compile(source, 3, {});
  const double reported = program->workspace_bytes(3);
  EXPECT_GT(reported, 8.0 * 4 * 250000);  // at least the values and tangents of a and b
  const SONGroup group(3);
  const Eigen::MatrixXd y = group.random(3);
  Eigen::MatrixXd basis(9, 3);
  for (int i = 0; i < 3; ++i) basis.middleRows(3 * i, 3) = y * group.hat(Eigen::Vector3d::Unit(i));
  const double measured = peak_growth_bytes([&] {
    Eigen::MatrixXd g, dgs;
    program->eval(y, 0.0, g);
    program->eval_along(y, 0.0, basis, dgs);
  });
  ASSERT_GT(measured, 0);
  EXPECT_GT(measured, reported / 2) << "reported " << reported << ", measured " << measured;
#if !defined(LIENEWTON_SANITIZED)
  // Not under AddressSanitizer: its allocator adds redzones and shadow to every block and keeps freed ones in
  // quarantine, by amounts that vary from run to run (2.6x the estimate on one machine, more on another).
  EXPECT_LT(measured, reported * 2) << "reported " << reported << ", measured " << measured;
#endif
  // Constants are the program's, not the workspace's: a large constant operand adds nothing per thread.
  const auto with_constant = user_field::compile("c = ones(500); a = y(ones(1,500), ones(1,500)) + c;"
                                                 "g = (y - y')*trace(a)", 3, {});
  const auto without = user_field::compile("a = y(ones(1,500), ones(1,500)) + 1; g = (y - y')*trace(a)", 3, {});
  EXPECT_EQ(with_constant->workspace_bytes(3), without->workspace_bytes(3));
}

// Three 1000x1000 tilings of y: legal alone (about 56 MB per evaluating thread), not on four threads at once.
constexpr const char* kThreeTilings =
    "a = y(ones(1,1000), ones(1,1000)); b = y(2*ones(1,1000), ones(1,1000)); c = y(3*ones(1,1000), ones(1,1000));"
    "g = (y - y')*(trace(a) + trace(b) + trace(c))";

// The message of the 413 naming g that validating the request must raise ("" when it raised none).
std::string too_large_for_g(const std::function<void()>& validate_request) {
  try {
    validate_request();
    ADD_FAILURE() << "validated";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.kind(), RequestError::Kind::too_large);
    EXPECT_EQ(e.field(), "g");
    return e.what();
  }
  return "";
}

TEST(UserFieldLimits, ASweepWhoseWorkspacesExceedTheBudgetIsRefusedNamingG) {
  SweepRequest req;
  req.problem.g = kThreeTilings;
  req.methods = {Method::newton_group};
  req.n = {3};
  req.h = {0.1, 0.2, 0.3, 0.4};
  req.threads = 4;
  const std::string message = too_large_for_g([&] { validate(req); });
  EXPECT_NE(message.find("4 threads"), std::string::npos) << message;
  req.threads = 1;
  EXPECT_NO_THROW(validate(req));
}

// Basin maps and work-precision diagrams evaluate g on several threads too: the budget counts them.
TEST(UserFieldLimits, BasinMapsAndWorkPrecisionCountTheirThreads) {
  BasinRequest basins;
  basins.solve.problem.g = kThreeTilings;
  basins.size = 4;
  basins.threads = 4;
  too_large_for_g([&] { validate(basins); });
  basins.threads = 1;
  EXPECT_NO_THROW(validate(basins));

  WorkPrecisionRequest wp;
  wp.problem.g = kThreeTilings;
  wp.choices = {{Integrator::implicit_euler, Method::newton_group, Differential::exact},
                {Integrator::dirk_cg2, Method::newton_group, Differential::exact}};
  wp.h = {0.25, 0.125};
  // Four runs on every core at once: beyond the budget where more than two threads run them.
  if (std::min(resolve_thread_count(0), 4) > 2)
    too_large_for_g([&] { validate(wp); });
  else
    EXPECT_NO_THROW(validate(wp));
}

}  // namespace
}  // namespace lienewton
