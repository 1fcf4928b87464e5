#pragma once
// A user's vector field g(y), written in a small, safe subset of MATLAB/Octave matrix syntax (the notation of the
// paper's section 5), compiled once for one n into a flat list of Eigen operations. Every value is a matrix whose
// size is known at compile time; values that depend on neither y nor t are folded into constants, values that
// depend on t alone are recomputed only when t changes, and equal instructions are shared. Evaluation is forward-mode at matrix level: each value carries its tangent, so
// dg_y(U) = d/dt g(y exp(tU)) at t = 0 is exact (the product rule per operation), not a difference quotient.
// No loops, no user functions, no I/O: a program's cost is bounded before it ever runs.
#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lienewton::user_field {

// Named numbers and matrices a program reads (e.g. an inertia matrix J).
using Parameters = std::map<std::string, Eigen::MatrixXd>;

// The bounds on a program, so a hostile one answers 422 before it runs.
inline constexpr std::size_t kMaxSourceBytes = 64 * 1024;
inline constexpr int kMaxNodes = 20000;          // syntax tree nodes
// The parser's depth: 2 for a statement, 2 per parenthesis or call, 3 per bracket, 1 per unary sign (63 calls, 42
// brackets deep).
inline constexpr int kMaxNesting = 128;
inline constexpr double kMaxElements = 1e6;      // entries of one value
inline constexpr double kMaxTotalElements = 4e6; // entries of all values together (and as many tangents)
inline constexpr double kMaxCost = 2e9;          // estimated flops of one evaluation of g and its tangent
inline constexpr std::size_t kMaxParameters = 64;
// Bytes of evaluation workspace one request may hold: a program's workspace_bytes times the threads that evaluate
// it at once (a sweep's threads). Beyond it the request is refused (413, field g).
inline constexpr double kMaxWorkspaceBytes = 128.0 * 1024 * 1024;

class Program;

// Compiles `source` for y of size n x n; the time t is an input of each evaluation. Throws RequestError
// (unprocessable, field "g", with the line and column of the fault) on a parse, size or limit error.
std::shared_ptr<const Program> compile(std::string_view source, int n, const Parameters& parameters);

// A parameter's value written as an expression of constants in the program's language ("pi/4", "1/3",
// "0.1*eye(3)", "[1 2; 3 4]'"): evaluated once, as a program's own constants are. It reads no y, t or other
// parameter. Throws RequestError (unprocessable, `field`, with the line and column in the text) otherwise.
Eigen::MatrixXd constant_value(std::string_view text, const std::string& field);

// Checks a parameter's name and value (a MATLAB identifier, finite entries, within the size limits); throws
// RequestError naming parameters.<name>.
void check_parameter(const std::string& name, const Eigen::MatrixXd& value);

struct Instruction;

class Program {
 public:
  ~Program();
  using In = Eigen::Ref<const Eigen::MatrixXd>;
  int n() const { return n_; }
  // g(t, y). Polls the current cancellation token (throws Cancelled).
  void eval(const In& y, double t, Eigen::MatrixXd& g) const;
  // g(t, y) and its derivative along dy: dg = d/ds g(t, y + s dy) at s = 0.
  void eval_with_tangent(const In& y, double t, const In& dy, Eigen::MatrixXd& g, Eigen::MatrixXd& dg) const;
  // Derivatives of g(t, .) at y along k directions dy_1 ... dy_k (on an algebra's basis U_d: dy_d = y U_d), in
  // passes of directions_per_pass(k) so that no more are held at once: direction(d, dy) writes dy_d (n x n),
  // derivative(d, dg) takes its derivative, both in order d = 0 ... k-1. The values once; per pass one tangent
  // pass of all its directions together (each product rule one product of wide matrices), or one direction at a
  // time when even one direction's stacked tangents would be too large.
  using Direction = std::function<void(Eigen::Index, Eigen::MatrixXd&)>;
  using Derivative = std::function<void(Eigen::Index, const Eigen::MatrixXd&)>;
  void eval_along(const In& y, double t, Eigen::Index k, const Direction& direction,
                  const Derivative& derivative) const;
  // The same for directions given stacked (n k x n, rows (d-1) n ... d n - 1 hold dy_d; dgs alike).
  void eval_along(const In& y, double t, const In& dys, Eigen::MatrixXd& dgs) const;
  Eigen::Index directions_per_pass(Eigen::Index k) const;
  std::size_t instructions() const;
  double cost() const { return cost_; }  // estimated flops of eval_with_tangent
  // Bytes one evaluating thread's workspace holds: the values of the slots that depend on y or t, the tangents of
  // those that depend on y, what a tangent pass keeps (f'(a), inverses), eval_along's stacked tangents of one pass
  // of `directions` directions, and the n x n matrices its caller holds (y, a direction, a derivative and its
  // check against the algebra). Constants are the program's own, shared by all threads, and not counted.
  double workspace_bytes(int directions) const;

  // Whether a thread keeps this program's workspace between evaluations (small programs: a solve calls g and dg
  // thousands of times); a larger one's is sized per call and freed after it, so no thread holds it after its
  // request.
  bool kept_per_thread() const { return elements_ <= kMaxCachedElements; }

  struct Workspace;

 private:
  friend class Compiler;
  Program();
  static constexpr double kMaxCachedElements = 65536;
  void run(const In& y, double t, const In* dy, Workspace& ws) const;
  void form_derivatives(Workspace& ws) const;
  void tangents_along(std::size_t i, Eigen::Index k, Workspace& ws) const;
  // Entries of the stacked tangents of one pass of eval_along: a pass takes as many directions as fit, at least
  // one, and a single direction beyond it goes through the one-direction tangents.
  static constexpr double kMaxStackedElements = 1 << 21;
  double varying_elements() const;
  void prepare(Workspace& ws) const;
  // The tangent of slot s after a run: its own, or a shared zero for a slot that does not depend on y.
  const Eigen::MatrixXd& tangent(const Workspace& ws, std::size_t s) const;
  const Eigen::MatrixXd& result(const Workspace& ws) const;
  template <class F>
  void with_workspace(F&& f) const;

  int n_ = 0;
  std::vector<Instruction> code_;       // the values that depend on y, in order
  std::vector<Instruction> time_code_;  // the values that depend on t and not on y, run when t changes
  // Per slot: size, whether it depends on y (it has a tangent), on t alone, and its value when on neither.
  std::vector<int> rows_, cols_;
  std::vector<bool> varies_, timed_;
  std::vector<Eigen::MatrixXd> constant_;
  // The tangent of every slot that does not depend on y, by size: zero, read by the instructions that take it.
  std::map<std::pair<int, int>, Eigen::MatrixXd> zeros_;
  int y_slot_ = 0, t_slot_ = 0, result_ = 0;
  double cost_ = 0;
  double elements_ = 0;  // entries of all slots
  std::uint64_t id_ = 0;  // tells a thread's cached workspace which program it was sized for
};

}  // namespace lienewton::user_field
