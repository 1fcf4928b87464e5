#include "program.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>

#include "../cancellation.hpp"
#include "../request_error.hpp"
#include "syntax.hpp"

namespace lienewton::user_field {

using Eigen::MatrixXd;

enum class Op {
  add, sub, neg, matmul, emul, ediv, epow, mpow, transpose, fn, diag_to_matrix, diag_of_matrix, triu, tril, trace,
  norm, cross, inv, left_div, right_div, skew, hcat, vcat, index, linear_index,
  antisym,  // a - a', fused from a - transpose(a)
  axpby     // alpha a + beta b, fused from sums of constant multiples (2*y - 5*y^2)
};
enum class Fn { sin, cos, tan, exp, log, sqrt, abs, tanh, sinh, cosh };

struct Instruction {
  Op op;
  int out;
  std::vector<int> in;
  long long k = 0;           // diag/triu/tril offset, mpow's power
  Fn fn = Fn::sin;
  unsigned varying = 0;      // bit i: operand i depends on y (has a tangent)
  double alpha = 1, beta = 1;  // axpby's coefficients
  std::vector<int> rows{}, cols{};  // index: the rows and columns taken (0-based); linear_index: rows alone
};

// One instruction's operands, tangents and results, bound to a workspace's slots once when it is sized.
struct Bound {
  std::vector<const MatrixXd*> x, dx;
  MatrixXd *out, *dout, *aux;
};

struct Program::Workspace {
  std::uint64_t id = 0;
  std::optional<double> time;  // the t the timed slots hold
  // The values hold g's pass at the y in y's slot (and the time): a further call at that y forms tangents only.
  // derivatives: the aux slots hold f'(a) of the entrywise functions too (a tangent pass left them).
  bool holds_y = false, holds_derivatives = false;
  // Per slot: value, tangent, and what a tangent pass reuses from the value pass (f'(a) of an entrywise
  // function, the inverse behind \ and /).
  std::vector<MatrixXd> val, tan, aux;
  std::vector<Bound> code, time_code;
  // eval_along's tangents of k directions per slot that depends on y, stacked ((rows k) x cols; empty for the
  // others), sized for stacked_k directions; and the operands of an instruction taken one direction at a time.
  Eigen::Index stacked_k = -1;
  bool stacked_fits = false;
  std::vector<MatrixXd> stacked, scratch;
  std::vector<const MatrixXd*> scratch_dx;
  MatrixXd scratch_out;
};

namespace {

std::string size_text(Eigen::Index r, Eigen::Index c) { return std::to_string(r) + "\u00d7" + std::to_string(c); }

// A number as a user wrote it: 3, 0.5, inf, -inf, nan (std::to_string writes 0.500000).
std::string number_text(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", x);
  return text;
}

// std::pow entry by entry: Eigen's vectorised pow trips GCC 12's false -Wuninitialized inside AVX-512 intrinsics.
struct Pow {
  double operator()(double a, double b) const { return std::pow(a, b); }
};

bool is_scalar(const MatrixXd& m) { return m.rows() == 1 && m.cols() == 1; }

// a op b entrywise, a 1x1 side spread over the other (MATLAB's scalar expansion).
template <class F>
void entrywise(const MatrixXd& a, const MatrixXd& b, MatrixXd& out, F f) {
  if (is_scalar(a) && !is_scalar(b))
    out = f(MatrixXd::Constant(b.rows(), b.cols(), a(0, 0)).array(), b.array()).matrix();
  else if (is_scalar(b) && !is_scalar(a))
    out = f(a.array(), MatrixXd::Constant(a.rows(), a.cols(), b(0, 0)).array()).matrix();
  else
    out = f(a.array(), b.array()).matrix();
}

void apply_fn(Fn fn, const MatrixXd& a, MatrixXd& out) {
  const auto x = a.array();
  switch (fn) {
    case Fn::sin: out = x.sin().matrix(); return;
    case Fn::cos: out = x.cos().matrix(); return;
    case Fn::tan: out = x.tan().matrix(); return;
    case Fn::exp: out = x.exp().matrix(); return;
    case Fn::log: out = x.log().matrix(); return;
    case Fn::sqrt: out = x.sqrt().matrix(); return;
    case Fn::abs: out = x.abs().matrix(); return;
    case Fn::tanh: out = x.tanh().matrix(); return;
    case Fn::sinh: out = x.sinh().matrix(); return;
    case Fn::cosh: out = x.cosh().matrix(); return;
  }
}

// f'(a) entrywise, given f(a) = fa: formed once with the values, so that each tangent f'(a) .* da is one product.
void derivative_fn(Fn fn, const MatrixXd& a, const MatrixXd& fa, MatrixXd& out) {
  const auto x = a.array(), f = fa.array();
  switch (fn) {
    case Fn::sin: out = x.cos().matrix(); return;
    case Fn::cos: out = (-x.sin()).matrix(); return;
    case Fn::tan: out = (1.0 + f.square()).matrix(); return;
    case Fn::exp: out = fa; return;
    case Fn::log: out = x.inverse().matrix(); return;
    case Fn::sqrt: out = (0.5 / f).matrix(); return;
    case Fn::abs: out = x.sign().matrix(); return;
    case Fn::tanh: out = (1.0 - f.square()).matrix(); return;
    case Fn::sinh: out = x.cosh().matrix(); return;
    case Fn::cosh: out = x.sinh().matrix(); return;
  }
}

// sin and cos are formed with their derivatives, one sincos per entry, at about the price of the value alone: Newton
// asks for dg_y at the y of each g(y).
bool forms_derivative_with_value(Fn fn) { return fn == Fn::sin || fn == Fn::cos; }

// sin(a) or cos(a) with its derivative.
void sin_cos(Fn fn, const MatrixXd& a, MatrixXd& out, MatrixXd& derivative) {
  out.resize(a.rows(), a.cols());
  derivative.resize(a.rows(), a.cols());
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    double s, c;
    ::sincos(a(i), &s, &c);
    out(i) = fn == Fn::sin ? s : c;
    derivative(i) = fn == Fn::sin ? c : -s;
  }
}

// out = a * b, or out += a * b. Square products of small n run on fixed-size kernels: at n = 3 the dynamic-size
// product's dispatch costs more than the product itself.
template <int N>
void fixed_product(const MatrixXd& a, const MatrixXd& b, MatrixXd& out, bool add) {
  using M = Eigen::Matrix<double, N, N>;
  const Eigen::Map<const M> p(a.data()), q(b.data());
  Eigen::Map<M> o(out.data());
  if (add) o.noalias() += p * q;
  else o.noalias() = p * q;
}
void product(const MatrixXd& a, const MatrixXd& b, MatrixXd& out, bool add = false) {
  if (!add) out.resize(a.rows(), b.cols());
  if (a.rows() == a.cols() && b.rows() == a.rows() && b.cols() == a.rows()) switch (a.rows()) {
      case 2: return fixed_product<2>(a, b, out, add);
      case 3: return fixed_product<3>(a, b, out, add);
      case 4: return fixed_product<4>(a, b, out, add);
      default: break;
    }
  if (add) out.noalias() += a * b;
  else out.noalias() = a * b;
}

// The inverse of a, NaN where a is singular to working precision (MATLAB warns and answers Inf; a solve would
// go on with garbage, so the iteration stops as non-finite instead).
MatrixXd inverse(const MatrixXd& a) {
  const Eigen::PartialPivLU<MatrixXd> lu(a);
  if (!(lu.rcond() > std::numeric_limits<double>::epsilon())) return MatrixXd::Constant(a.rows(), a.cols(), NAN);
  return lu.inverse();
}

MatrixXd cross3(const MatrixXd& a, const MatrixXd& b) {
  const Eigen::Vector3d u = a.reshaped(), v = b.reshaped();
  const Eigen::Vector3d w = u.cross(v);
  return w.reshaped(a.rows(), a.cols());
}

// The linear operations, applied alike to values and to tangents.
void apply_linear(const Instruction& ins, const std::vector<const MatrixXd*>& x, MatrixXd& out) {
  const MatrixXd& a = *x[0];
  switch (ins.op) {
    case Op::add: entrywise(a, *x[1], out, [](const auto& p, const auto& q) { return p + q; }); return;
    case Op::sub: entrywise(a, *x[1], out, [](const auto& p, const auto& q) { return p - q; }); return;
    case Op::neg: out = -a; return;
    case Op::transpose: out = a.transpose(); return;
    case Op::diag_to_matrix: {
      out.setZero();
      const long long k = ins.k;
      for (Eigen::Index i = 0; i < a.size(); ++i) out(i + (k < 0 ? -k : 0), i + (k > 0 ? k : 0)) = a(i);
      return;
    }
    case Op::diag_of_matrix: {
      const long long k = ins.k;
      for (Eigen::Index i = 0; i < out.rows(); ++i) out(i, 0) = a(i + (k < 0 ? -k : 0), i + (k > 0 ? k : 0));
      return;
    }
    case Op::triu:
    case Op::tril:
      for (Eigen::Index j = 0; j < a.cols(); ++j)
        for (Eigen::Index i = 0; i < a.rows(); ++i) {
          const bool keep = ins.op == Op::triu ? j - i >= ins.k : j - i <= ins.k;
          out(i, j) = keep ? a(i, j) : 0.0;
        }
      return;
    case Op::trace: out(0, 0) = a.trace(); return;
    case Op::skew: out = 0.5 * (a - a.transpose()); return;
    case Op::antisym: out = a - a.transpose(); return;
    case Op::axpby: out = ins.alpha * a + ins.beta * *x[1]; return;
    case Op::hcat: {
      if (out.size() == 0) return;  // nothing to copy, and no data to offset into (an empty matrix's is null)
      Eigen::Index c = 0;
      for (const MatrixXd* p : x) {
        out.middleCols(c, p->cols()) = *p;
        c += p->cols();
      }
      return;
    }
    case Op::vcat: {
      if (out.size() == 0) return;
      Eigen::Index r = 0;
      for (const MatrixXd* p : x) {
        out.middleRows(r, p->rows()) = *p;
        r += p->rows();
      }
      return;
    }
    case Op::index:
      for (std::size_t j = 0; j < ins.cols.size(); ++j)
        for (std::size_t i = 0; i < ins.rows.size(); ++i)
          out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = a(ins.rows[i], ins.cols[j]);
      return;
    case Op::linear_index:
      for (std::size_t m = 0; m < ins.rows.size(); ++m) out(static_cast<Eigen::Index>(m)) = a(ins.rows[m]);
      return;
    default: return;
  }
}

bool is_linear(Op op) {
  switch (op) {
    case Op::add: case Op::sub: case Op::neg: case Op::transpose: case Op::diag_to_matrix: case Op::diag_of_matrix:
    case Op::triu: case Op::tril: case Op::trace: case Op::skew: case Op::hcat: case Op::vcat: case Op::index:
    case Op::linear_index: case Op::antisym: case Op::axpby:
      return true;
    default: return false;
  }
}

// a^k for an integer k by repeated squaring, with its tangent when da is given.
void matrix_power(const MatrixXd& a0, const MatrixXd* da0, long long k, MatrixXd& out, MatrixXd* dout) {
  MatrixXd base = a0, dbase;
  if (da0) dbase = *da0;
  if (k < 0) {
    base = inverse(a0);
    if (da0) dbase = -base * *da0 * base;
    k = -k;
  }
  out = MatrixXd::Identity(a0.rows(), a0.cols());
  if (dout) dout->setZero(a0.rows(), a0.cols());
  MatrixXd t;
  while (k > 0) {
    if (k & 1) {
      if (dout) {
        t.noalias() = *dout * base;
        t.noalias() += out * dbase;
        *dout = t;
      }
      t.noalias() = out * base;
      out = t;
    }
    k >>= 1;
    if (k == 0) break;
    if (dout) {
      t.noalias() = dbase * base;
      t.noalias() += base * dbase;
      dbase = t;
    }
    t.noalias() = base * base;
    base = t;
  }
}

// c = a .* b (a 1x1 side spread) and dc = da .* b + a .* db, a term skipped where its operand is constant.
void entrywise_product(const MatrixXd& a, const MatrixXd& b, MatrixXd& out, const std::vector<const MatrixXd*>* dx,
                       MatrixXd* dout, bool a_varies, bool b_varies, bool known) {
  const auto times = [](const auto& p, const auto& q) { return p * q; };
  if (!known) entrywise(a, b, out, times);
  if (!dx) return;
  if (!b_varies) {
    entrywise(*(*dx)[0], b, *dout, times);
    return;
  }
  entrywise(a, *(*dx)[1], *dout, times);
  if (!a_varies) return;
  MatrixXd t;
  entrywise(*(*dx)[0], b, t, times);
  *dout += t;
}

// The value of one instruction from its operands' values, and (when dx is given) its tangent from theirs. known:
// out already holds the value, and aux what the value pass left for the tangents (a further call at the same y),
// so only the tangent is formed. Folding constants and the values of t pass no tangents.
void apply(const Instruction& ins, const std::vector<const MatrixXd*>& x, MatrixXd& out,
           const std::vector<const MatrixXd*>* dx, MatrixXd* dout, MatrixXd& aux, bool known = false) {
  auto var = [&](unsigned i) { return ((ins.varying >> i) & 1u) != 0; };
  if (is_linear(ins.op)) {
    if (!known) apply_linear(ins, x, out);
    if (dx) apply_linear(ins, *dx, *dout);
    return;
  }
  const MatrixXd& a = *x[0];
  switch (ins.op) {
    case Op::matmul: {
      const MatrixXd& b = *x[1];
      if (is_scalar(a) || is_scalar(b)) {
        entrywise_product(a, b, out, dx, dout, var(0), var(1), known);
        return;
      }
      if (!known) product(a, b, out);
      if (dx) {
        if (var(0)) product(*(*dx)[0], b, *dout);
        else dout->setZero();
        if (var(1)) product(a, *(*dx)[1], *dout, true);
      }
      return;
    }
    case Op::emul: entrywise_product(a, *x[1], out, dx, dout, var(0), var(1), known); return;
    case Op::ediv: {
      const MatrixXd& b = *x[1];
      if (!known) entrywise(a, b, out, [](const auto& p, const auto& q) { return p / q; });
      if (dx) {
        entrywise(*(*dx)[0], b, *dout, [](const auto& p, const auto& q) { return p / q; });
        if (var(1)) {  // - (a ./ b) .* db ./ b
          MatrixXd t, s;
          entrywise(out, *(*dx)[1], t, [](const auto& p, const auto& q) { return p * q; });
          entrywise(t, b, s, [](const auto& p, const auto& q) { return p / q; });
          *dout -= s;
        }
      }
      return;
    }
    case Op::epow: {
      const MatrixXd& b = *x[1];
      if (!known) entrywise(a, b, out, [](const auto& p, const auto& q) { return p.binaryExpr(q, Pow{}); });
      if (dx) {
        MatrixXd t;
        entrywise(a, b, t, [](const auto& p, const auto& q) { return q * p.binaryExpr(q - 1.0, Pow{}); });
        entrywise(t, *(*dx)[0], *dout, [](const auto& p, const auto& q) { return p * q; });
        if (var(1)) {  // + a.^b .* log(a) .* db
          MatrixXd l, s;
          entrywise(out, a, l, [](const auto& p, const auto& q) { return p * q.log(); });
          entrywise(l, *(*dx)[1], s, [](const auto& p, const auto& q) { return p * q; });
          *dout += s;
        }
      }
      return;
    }
    case Op::mpow: {
      MatrixXd value;
      matrix_power(a, dx ? (*dx)[0] : nullptr, ins.k, known ? value : out, dout);
      return;
    }
    case Op::fn:
      if (!known) {
        if (forms_derivative_with_value(ins.fn)) {
          sin_cos(ins.fn, a, out, aux);
        } else {
          apply_fn(ins.fn, a, out);
          if (dx) derivative_fn(ins.fn, a, out, aux);
        }
      }
      if (dx) *dout = (aux.array() * (*dx)[0]->array()).matrix();
      return;
    case Op::norm: {
      if (a.size() == 0) {  // MATLAB: the norm of an empty matrix is 0, and so is its change
        out(0, 0) = 0;
        if (dx) (*dout)(0, 0) = 0;
        return;
      }
      if (a.rows() == 1 || a.cols() == 1) {
        const double r = a.norm();
        out(0, 0) = r;
        if (dx) (*dout)(0, 0) = r > 0 ? a.reshaped().dot((*dx)[0]->reshaped()) / r : 0.0;
        return;
      }
      const Eigen::JacobiSVD<MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
      out(0, 0) = svd.singularValues()(0);
      if (dx) (*dout)(0, 0) = svd.matrixU().col(0).dot(*(*dx)[0] * svd.matrixV().col(0));
      return;
    }
    case Op::cross:
      out = cross3(a, *x[1]);
      if (dx) *dout = cross3(*(*dx)[0], *x[1]) + cross3(a, *(*dx)[1]);
      return;
    case Op::inv:
      if (!known) out = inverse(a);
      if (dx) *dout = -out * *(*dx)[0] * out;
      return;
    case Op::left_div: {  // X = a \ b, dX = a \ (db - da X); aux = a^-1
      if (!known) {
        aux = inverse(a);
        product(aux, *x[1], out);
      }
      if (!dx) return;
      if (var(0)) *dout = aux * (*(*dx)[1] - *(*dx)[0] * out);
      else product(aux, *(*dx)[1], *dout);
      return;
    }
    case Op::right_div: {  // X = a / b, dX = (da - X db) / b; aux = b^-1
      if (!known) {
        aux = inverse(*x[1]);
        product(a, aux, out);
      }
      if (!dx) return;
      if (var(1)) *dout = (*(*dx)[0] - out * *(*dx)[1]) * aux;
      else product(*(*dx)[0], aux, *dout);
      return;
    }
    default: return;
  }
}

std::atomic<std::uint64_t> next_program_id{1};

const char* const kFunctions[] = {"sin",  "cos",  "tan",   "exp",  "log",  "sqrt", "abs", "tanh", "sinh",
                                  "cosh", "diag", "triu",  "tril", "trace", "eye", "zeros", "ones", "size",
                                  "norm", "cross", "inv",  "skew", "transpose"};

bool is_function(const std::string& name) {
  for (const char* f : kFunctions)
    if (name == f) return true;
  return false;
}

}  // namespace

// Turns a syntax tree into a Program: names resolved, sizes checked, constants folded, equal instructions shared.
class Compiler {
 public:
  Compiler(const Syntax& syntax, int n, const Parameters& parameters) : s_(syntax), p_(new Program()) {
    p_->n_ = n;
    p_->y_slot_ = new_slot(n, n, Class::varies, MatrixXd());
    names_["y"] = p_->y_slot_;
    p_->t_slot_ = new_slot(1, 1, Class::timed, MatrixXd());
    names_["t"] = p_->t_slot_;
    names_["pi"] = constant(MatrixXd::Constant(1, 1, std::numbers::pi));
    for (const auto& [name, value] : parameters) names_[name] = constant(value);
  }

  // The value of a program that reads no y and no t: its last statement's (or g's), folded when compiled.
  // A parameter's value is its text's last statement, an expression; those before it may only name values for it
  // ("c = cos(pi); [c; 2*c]"). Another expression before it ("1,2", "2\n3") or an assignment last ("a = 2") would
  // leave a value the user did not write as the value.
  MatrixXd constant_result() {
    if (s_.statements.empty()) fail_at(1, 1, "the value is empty: write a number, a matrix or an expression of them");
    const int last = s_.statements.back();
    for (int st : s_.statements) {
      if (st == last) break;
      const Node& nd = node(st);
      if (nd.kind != NodeKind::assign)
        fail(st, "a parameter's value is one expression, and another follows this one (a matrix's entries go "
                 "inside brackets: [1, 2] or [1 2; 3 4])");
      names_[nd.text] = expr(nd.kids[0]);
    }
    if (node(last).kind == NodeKind::assign)
      fail(last, "a parameter's value ends with an expression, not an assignment: write the value alone");
    const int result = expr(last);
    if (!fixed(result)) fail(last, "a parameter is a constant: its value cannot read y or t");
    return value(result);
  }

  std::shared_ptr<const Program> run() {
    int result = -1, result_statement = -1;
    bool assigned_g = false;
    for (int st : s_.statements) {
      const Node& node = s_.nodes[static_cast<std::size_t>(st)];
      if (node.kind == NodeKind::assign) {
        const int v = expr(node.kids[0]);
        names_[node.text] = v;
        if (node.text == "g") {
          result = v;
          result_statement = st;
          assigned_g = true;
        } else if (!assigned_g) {
          result = -1;
        }
      } else {
        const int v = expr(st);
        if (!assigned_g) result = v, result_statement = st;
      }
    }
    if (result < 0)
      fail_at(1, 1, s_.statements.empty() ? "the program is empty: assign g = ... (a matrix the size of y)"
                                          : "the program gives no value: assign g = ... or end with an expression");
    const int n = p_->n_;
    const std::size_t r = static_cast<std::size_t>(result);
    if (p_->rows_[r] != n || p_->cols_[r] != n)
      fail(result_statement, "g must be n\u00d7n (" + size_text(n, n) + ", the size of y), got " +
                        size_text(p_->rows_[r], p_->cols_[r]));
    p_->result_ = result;
    drop_dead();
    const auto shape = [&](int slot) {
      return std::pair{p_->rows_[static_cast<std::size_t>(slot)], p_->cols_[static_cast<std::size_t>(slot)]};
    };
    p_->zeros_.try_emplace(shape(result), MatrixXd::Zero(n, n));
    for (const Instruction& ins : p_->code_)
      for (int i : ins.in)
        if (!varies(i)) p_->zeros_.try_emplace(shape(i), MatrixXd::Zero(rows(i), cols(i)));
    p_->cost_ = 3.0 * cost_;
    p_->elements_ = total_elements_;
    return std::shared_ptr<const Program>(p_.release());
  }

 private:
  const Node& node(int i) const { return s_.nodes[static_cast<std::size_t>(i)]; }
  [[noreturn]] void fail(int at, const std::string& message) const {
    fail_at(node(at).line, node(at).column, message);
  }

  enum class Class { fixed, timed, varies };  // known when compiled; depends on t alone; depends on y
  int new_slot(Eigen::Index rows, Eigen::Index cols, Class c, MatrixXd value) {
    const double elements = double(rows) * double(cols);
    total_elements_ += elements;
    if (elements > kMaxElements || total_elements_ > kMaxTotalElements)
      fail_at(at_line_, at_column_, "the program's values are too large (" + size_text(rows, cols) + "; at most " +
                                        std::to_string(static_cast<long long>(kMaxElements)) + " entries each)");
    p_->rows_.push_back(static_cast<int>(rows));
    p_->cols_.push_back(static_cast<int>(cols));
    p_->varies_.push_back(c == Class::varies);
    p_->timed_.push_back(c == Class::timed);
    p_->constant_.push_back(std::move(value));
    return static_cast<int>(p_->rows_.size()) - 1;
  }
  // Equal numbers share one slot, so 2*y written twice is one instruction.
  int constant(MatrixXd value) {
    const auto r = value.rows(), c = value.cols();
    if (r != 1 || c != 1) return new_slot(r, c, Class::fixed, std::move(value));
    const double x = value(0, 0);
    if (auto it = numbers_.find(x); it != numbers_.end() && !std::signbit(x)) return it->second;
    const int s = new_slot(1, 1, Class::fixed, std::move(value));
    if (std::isfinite(x) && !std::signbit(x)) numbers_.emplace(x, s);
    return s;
  }
  Eigen::Index rows(int s) const { return p_->rows_[static_cast<std::size_t>(s)]; }
  Eigen::Index cols(int s) const { return p_->cols_[static_cast<std::size_t>(s)]; }
  bool varies(int s) const { return p_->varies_[static_cast<std::size_t>(s)]; }
  bool timed(int s) const { return p_->timed_[static_cast<std::size_t>(s)]; }
  bool fixed(int s) const { return !varies(s) && !timed(s); }  // known when compiled
  bool scalar(int s) const { return rows(s) == 1 && cols(s) == 1; }
  const MatrixXd& value(int s) const { return p_->constant_[static_cast<std::size_t>(s)]; }

  // An instruction of the given result size: folded when its operands are constant, shared when emitted before.
  int emit(Instruction ins, Eigen::Index r, Eigen::Index c, double flops, int at) {
    at_line_ = node(at).line;
    at_column_ = node(at).column;
    cost_ += flops + double(r) * double(c);
    if (3.0 * cost_ > kMaxCost)
      fail(at, "the program is too costly: about " + std::to_string(static_cast<long long>(3.0 * cost_)) +
                   " operations per evaluation, at most " + std::to_string(static_cast<long long>(kMaxCost)));
    poll();
    bool any_varies = false, any_timed = false;
    for (std::size_t i = 0; i < ins.in.size(); ++i) {
      any_varies = any_varies || varies(ins.in[i]);
      any_timed = any_timed || timed(ins.in[i]);
      if (i < 2 && varies(ins.in[i])) ins.varying |= 1u << i;
    }
    if (!any_varies && !any_timed) {
      std::vector<const MatrixXd*> x;
      for (int i : ins.in) x.push_back(&value(i));
      MatrixXd out(r, c), aux;
      apply(ins, x, out, nullptr, nullptr, aux);
      return constant(std::move(out));
    }
    std::string key = std::to_string(static_cast<int>(ins.op)) + ":" + std::to_string(static_cast<int>(ins.fn)) + ":" +
                      std::to_string(ins.k) + ":" + std::to_string(std::bit_cast<std::uint64_t>(ins.alpha)) + ":" +
                      std::to_string(std::bit_cast<std::uint64_t>(ins.beta));
    for (int i : ins.in) {  // appended: GCC 12 reports a false -Wrestrict on "," + std::to_string(...)
      key += ',';
      key += std::to_string(i);
    }
    key += "|";
    for (int i : ins.rows) key += std::to_string(i) + " ";
    key += "|";
    for (int i : ins.cols) key += std::to_string(i) + " ";
    if (auto it = shared_.find(key); it != shared_.end()) return it->second;
    ins.out = new_slot(r, c, any_varies ? Class::varies : Class::timed, MatrixXd());
    shared_.emplace(std::move(key), ins.out);
    auto& code = any_varies ? p_->code_ : p_->time_code_;
    code.push_back(std::move(ins));
    return code.back().out;
  }
  int emit(Op op, std::vector<int> in, Eigen::Index r, Eigen::Index c, double flops, int at, long long k = 0) {
    Instruction ins{op, -1, std::move(in)};
    ins.k = k;
    return emit(std::move(ins), r, c, flops, at);
  }

  // A compile-time integer (a size, an offset, a power).
  long long integer(int at, int slot, const char* what, long long lo, long long hi) {
    if (!fixed(slot) || !scalar(slot)) fail(at, std::string(what) + " must be a constant number");
    const double v = value(slot)(0, 0);
    if (!(v == std::floor(v)) || v < double(lo) || v > double(hi))
      fail(at, std::string(what) + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<long long>(v);
  }

  int elementwise(Op op, int a, int b, int at, const char* symbol) {
    if (!(scalar(a) || scalar(b) || (rows(a) == rows(b) && cols(a) == cols(b))))
      fail(at, "matrix sizes " + size_text(rows(a), cols(a)) + " and " + size_text(rows(b), cols(b)) +
                   " do not agree for " + symbol);
    const Eigen::Index r = scalar(a) ? rows(b) : rows(a), c = scalar(a) ? cols(b) : cols(a);
    return emit(op, {a, b}, r, c, double(r) * double(c) * (op == Op::epow ? 20 : 1), at);
  }

  int binary(int at, int a, int b) {
    const std::string& op = node(at).text;
    if (op == "^") return power(at, a, b);
    if (op == "+" || op == "-")
      if (const int fused = fused_sum(a, b, op == "-", at); fused >= 0) return fused;
    if (op == "+") return elementwise(Op::add, a, b, at, "+");
    if (op == "-") return elementwise(Op::sub, a, b, at, "-");
    if (op == ".*") return scaled(elementwise(Op::emul, a, b, at, ".*"), a, b);
    if (op == "./") return elementwise(Op::ediv, a, b, at, "./");
    if (op == ".^") return elementwise(Op::epow, a, b, at, ".^");
    if (op == "*") {
      if (scalar(a) || scalar(b)) return scaled(elementwise(Op::matmul, a, b, at, "*"), a, b);
      if (cols(a) != rows(b))
        fail(at, "matrix sizes " + size_text(rows(a), cols(a)) + " and " + size_text(rows(b), cols(b)) +
                     " do not agree for * (columns of the left must equal rows of the right; use .* for entrywise)");
      return emit(Op::matmul, {a, b}, rows(a), cols(b), 2.0 * double(rows(a)) * double(cols(a)) * double(cols(b)), at);
    }
    if (op == "/") {
      if (scalar(b)) return elementwise(Op::ediv, a, b, at, "/");
      if (rows(b) != cols(b)) fail(at, "a / B needs a square B, got " + size_text(rows(b), cols(b)));
      if (cols(a) != cols(b))
        fail(at, "matrix sizes " + size_text(rows(a), cols(a)) + " and " + size_text(rows(b), cols(b)) +
                     " do not agree for /");
      const double m = double(rows(b));
      return emit(Op::right_div, {a, b}, rows(a), cols(b), 4.0 * m * m * m + 4.0 * double(rows(a)) * m * m, at);
    }
    if (op == "\\") {
      if (scalar(a)) return elementwise(Op::ediv, b, a, at, "\\");
      if (rows(a) != cols(a)) fail(at, "A \\ b needs a square A, got " + size_text(rows(a), cols(a)));
      if (rows(a) != rows(b))
        fail(at, "matrix sizes " + size_text(rows(a), cols(a)) + " and " + size_text(rows(b), cols(b)) +
                     " do not agree for \\");
      const double m = double(rows(a));
      return emit(Op::left_div, {a, b}, rows(a), cols(b), 4.0 * m * m * m + 4.0 * double(cols(b)) * m * m, at);
    }
    fail(at, "unknown operator " + op);
  }

  // Where a value is c * x for a constant number c and a y-dependent matrix x (so that sums of such fuse).
  int scaled(int out, int a, int b) {
    if (fixed(a) && scalar(a) && varies(b) && !scalar(b)) multiple_[out] = {b, value(a)(0, 0)};
    if (fixed(b) && scalar(b) && varies(a) && !scalar(a)) multiple_[out] = {a, value(b)(0, 0)};
    return out;
  }
  // a + b or a - b of y-dependent matrices of one size as one instruction: a - a' (antisym), or
  // alpha x + beta w where a = alpha x and b = beta w are constant multiples; -1 when neither applies.
  int fused_sum(int a, int b, bool minus, int at) {
    if (!varies(a) || !varies(b) || rows(a) != rows(b) || cols(a) != cols(b) || scalar(a)) return -1;
    const double flops = 3.0 * double(rows(a)) * double(cols(a));
    if (auto it = transposed_.find(b); minus && it != transposed_.end() && it->second == a)
      return emit(Op::antisym, {a}, rows(a), cols(a), flops, at);
    const auto ma = multiple_.find(a), mb = multiple_.find(b);
    if (ma == multiple_.end() && mb == multiple_.end()) return -1;
    Instruction ins{Op::axpby, -1, {ma == multiple_.end() ? a : ma->second.first, mb == multiple_.end() ? b : mb->second.first}};
    ins.alpha = ma == multiple_.end() ? 1.0 : ma->second.second;
    ins.beta = (minus ? -1.0 : 1.0) * (mb == multiple_.end() ? 1.0 : mb->second.second);
    return emit(std::move(ins), rows(a), cols(a), flops, at);
  }
  int transposed(int out, int a) {
    if (varies(a)) transposed_[out] = a;
    return out;
  }

  // Drops the instructions nothing reads: the parts a fused sum replaced, assignments g does not use.
  void drop_dead() {
    std::vector<bool> live(p_->rows_.size(), false);
    live[static_cast<std::size_t>(p_->result_)] = true;
    for (std::vector<Instruction>* code : {&p_->code_, &p_->time_code_}) {
      std::vector<Instruction> kept;
      for (auto it = code->rbegin(); it != code->rend(); ++it) {
        if (!live[static_cast<std::size_t>(it->out)]) continue;
        for (int i : it->in) live[static_cast<std::size_t>(i)] = true;
        kept.push_back(std::move(*it));
      }
      std::reverse(kept.begin(), kept.end());
      *code = std::move(kept);
    }
  }

  // a^p: a scalar power entrywise, a square matrix to a constant integer power.
  int power(int at, int a, int p) {
    if (scalar(a) && scalar(p)) return elementwise(Op::epow, a, p, at, "^");
    if (!scalar(p)) fail(at, "in a^p, p must be a number (use .^ for entrywise powers)");
    if (rows(a) != cols(a)) fail(at, "a^p needs a square matrix, got " + size_text(rows(a), cols(a)) +
                                         " (use .^ for entrywise powers)");
    if (!fixed(p) || value(p)(0, 0) != std::floor(value(p)(0, 0)) || std::abs(value(p)(0, 0)) > 1e15)
      fail(at, "a matrix power y^p needs a constant integer p (use .^ for entrywise powers)");
    const long long k = static_cast<long long>(value(p)(0, 0));
    const double m = double(rows(a));
    if (k == 1) return a;
    if (k == 2) return emit(Op::matmul, {a, a}, rows(a), cols(a), 2.0 * m * m * m, at);  // y^2 is y*y, shared
    const double squarings = std::ceil(std::log2(double(std::llabs(k)) + 1.0));
    return emit(Op::mpow, {a}, rows(a), cols(a), 4.0 * squarings * 2.0 * m * m * m + (k < 0 ? 4 * m * m * m : 0), at,
                k);
  }

  int matrix(int at) {
    const Node& nd = node(at);
    std::vector<int> row_values;
    for (int r : nd.kids) {
      std::vector<int> parts;
      for (int e : node(r).kids) {
        const int v = expr(e);
        if (rows(v) == 0 && cols(v) == 0) continue;  // [a, []] is a
        if (!parts.empty() && rows(v) != rows(parts.front()))
          fail(e, "horizontal concatenation needs equal numbers of rows: " + size_text(rows(parts.front()), cols(parts.front())) +
                      " and " + size_text(rows(v), cols(v)));
        parts.push_back(v);
      }
      if (parts.empty()) continue;
      if (parts.size() == 1) {
        row_values.push_back(parts.front());
        continue;
      }
      Eigen::Index c = 0;
      for (int v : parts) c += cols(v);
      row_values.push_back(emit(Op::hcat, parts, rows(parts.front()), c, double(rows(parts.front())) * double(c), r));
    }
    if (row_values.empty()) return constant(MatrixXd(0, 0));
    if (row_values.size() == 1) return row_values.front();
    Eigen::Index r = 0;
    for (int v : row_values) {
      if (cols(v) != cols(row_values.front()))
        fail(at, "vertical concatenation needs equal numbers of columns: " +
                     size_text(rows(row_values.front()), cols(row_values.front())) + " and " + size_text(rows(v), cols(v)));
      r += rows(v);
    }
    return emit(Op::vcat, row_values, r, cols(row_values.front()), double(r) * double(cols(row_values.front())), at);
  }

  int range(int at) {
    const Node& nd = node(at);
    std::vector<double> v;
    for (int k : nd.kids) {
      const int s = expr(k);
      if (!fixed(s) || !scalar(s)) fail(k, "a range a:b or a:step:b needs constant numbers");
      v.push_back(value(s)(0, 0));
    }
    const double start = v[0], step = v.size() == 3 ? v[1] : 1.0, stop = v.back();
    const double count = step == 0 || (stop - start) / step < 0 ? 0 : std::floor((stop - start) / step + 1e-10) + 1;
    if (!(count <= kMaxElements)) fail(at, "the range has too many elements");
    MatrixXd out(1, static_cast<Eigen::Index>(count));
    for (Eigen::Index i = 0; i < out.cols(); ++i) out(0, i) = start + double(i) * step;
    return constant(std::move(out));
  }

  // The positions an index argument selects in a dimension of `extent` (0-based).
  std::vector<int> positions(int arg, Eigen::Index extent, MatrixXd* shape) {
    std::vector<int> out;
    if (node(arg).kind == NodeKind::colon) {
      for (Eigen::Index i = 0; i < extent; ++i) out.push_back(static_cast<int>(i));
      if (shape) *shape = MatrixXd(extent, 1);
      return out;
    }
    ends_.push_back(extent);
    const int s = expr(arg);
    ends_.pop_back();
    if (!fixed(s)) fail(arg, "indices must be constant (numbers, ranges such as 1:3, end, :)");
    for (Eigen::Index i = 0; i < value(s).size(); ++i) {
      const double x = value(s)(i);
      if (!std::isfinite(x) || x != std::floor(x) || x < 1)
        fail(arg, "index " + number_text(x) + " is not a positive integer");
      if (x > double(extent))
        fail(arg, "index " + number_text(x) + " exceeds the size " +
                      std::to_string(extent));
      out.push_back(static_cast<int>(x) - 1);
    }
    if (shape) *shape = value(s);
    return out;
  }

  int index(int at, int a) {
    const Node& nd = node(at);
    if (nd.kids.size() == 2) {
      Instruction ins{Op::index, -1, {a}};
      ins.rows = positions(nd.kids[0], rows(a), nullptr);
      ins.cols = positions(nd.kids[1], cols(a), nullptr);
      const auto r = static_cast<Eigen::Index>(ins.rows.size()), c = static_cast<Eigen::Index>(ins.cols.size());
      return emit(std::move(ins), r, c, double(r) * double(c), at);
    }
    if (nd.kids.size() != 1) fail(at, "an index takes one or two subscripts, as in y(2,3) or y(:,1)");
    MatrixXd shape;
    Instruction ins{Op::linear_index, -1, {a}};
    ins.rows = positions(nd.kids[0], rows(a) * cols(a), &shape);
    const auto m = static_cast<Eigen::Index>(ins.rows.size());
    Eigen::Index r = m, c = 1;  // a(:) and a matrix's a(k) follow the index's shape; a vector's keep its own
    if (node(nd.kids[0]).kind != NodeKind::colon) {
      if (rows(a) == 1 && cols(a) != 1) r = 1, c = m;
      else if (cols(a) == 1 && rows(a) != 1) r = m, c = 1;
      else r = shape.rows(), c = shape.cols();
    }
    return emit(std::move(ins), r, c, double(m), at);
  }

  void arity(int at, std::size_t lo, std::size_t hi) {
    const std::size_t k = node(at).kids.size();
    if (k < lo || k > hi)
      fail(at, node(at).text + " takes " + (lo == hi ? std::to_string(lo) : std::to_string(lo) + " or " + std::to_string(hi)) +
                   " argument" + (hi == 1 ? "" : "s") + ", got " + std::to_string(k));
  }

  // eye/zeros/ones(m), (m, n) or (size(...)).
  std::pair<Eigen::Index, Eigen::Index> shape_arguments(int at) {
    const Node& nd = node(at);
    if (nd.kids.empty()) return {1, 1};
    std::vector<int> s;
    for (int k : nd.kids) s.push_back(expr(k));
    const long long big = static_cast<long long>(kMaxElements);
    if (s.size() == 1 && fixed(s[0]) && rows(s[0]) == 1 && cols(s[0]) == 2) {
      const MatrixXd& v = value(s[0]);
      if (v(0) != std::floor(v(0)) || v(1) != std::floor(v(1)) || v(0) < 0 || v(1) < 0 || v(0) > double(big) ||
          v(1) > double(big))
        fail(at, nd.text + "'s size must be non-negative integers");
      return {static_cast<Eigen::Index>(v(0)), static_cast<Eigen::Index>(v(1))};
    }
    if (s.size() > 2) fail(at, nd.text + " takes at most 2 sizes");
    const long long m = integer(nd.kids[0], s[0], "a size", 0, big);
    const long long c = s.size() == 2 ? integer(nd.kids[1], s[1], "a size", 0, big) : m;
    return {static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(c)};
  }

  int call(int at) {
    const Node& nd = node(at);
    const std::string& f = nd.text;
    if (auto it = names_.find(f); it != names_.end()) return index(at, it->second);
    if (!is_function(f)) fail(at, "unknown function or variable '" + f + "'");
    static const std::pair<const char*, Fn> kElementwise[] = {
        {"sin", Fn::sin}, {"cos", Fn::cos}, {"tan", Fn::tan}, {"exp", Fn::exp}, {"log", Fn::log},
        {"sqrt", Fn::sqrt}, {"abs", Fn::abs}, {"tanh", Fn::tanh}, {"sinh", Fn::sinh}, {"cosh", Fn::cosh}};
    for (const auto& [name, fn] : kElementwise) {
      if (f != name) continue;
      arity(at, 1, 1);
      const int a = expr(nd.kids[0]);
      Instruction ins{Op::fn, -1, {a}};
      ins.fn = fn;
      return emit(std::move(ins), rows(a), cols(a), 20.0 * double(rows(a)) * double(cols(a)), at);
    }
    if (f == "eye" || f == "zeros" || f == "ones") {
      const auto [r, c] = shape_arguments(at);
      if (double(r) * double(c) > kMaxElements) fail(at, f + "(" + size_text(r, c) + ") is too large");
      at_line_ = nd.line, at_column_ = nd.column;
      if (f == "eye") return constant(MatrixXd::Identity(r, c));
      return constant(MatrixXd::Constant(r, c, f == "ones" ? 1.0 : 0.0));
    }
    if (f == "size") {
      arity(at, 1, 2);
      const int a = expr(nd.kids[0]);
      if (nd.kids.size() == 2) {
        const long long d = integer(nd.kids[1], expr(nd.kids[1]), "size's dimension", 1, 2);
        return constant(MatrixXd::Constant(1, 1, double(d == 1 ? rows(a) : cols(a))));
      }
      MatrixXd v(1, 2);
      v << double(rows(a)), double(cols(a));
      return constant(std::move(v));
    }
    if (f == "diag" || f == "triu" || f == "tril") {
      arity(at, 1, 2);
      const int a = expr(nd.kids[0]);
      const long long big = static_cast<long long>(kMaxElements);
      const long long k = nd.kids.size() == 2 ? integer(nd.kids[1], expr(nd.kids[1]), "the diagonal's offset", -big, big) : 0;
      const double flops = double(rows(a)) * double(cols(a));
      if (f != "diag") return emit(f == "triu" ? Op::triu : Op::tril, {a}, rows(a), cols(a), flops, at, k);
      if (rows(a) == 1 || cols(a) == 1) {
        const Eigen::Index m = rows(a) * cols(a) + static_cast<Eigen::Index>(std::llabs(k));
        if (double(m) * double(m) > kMaxElements) fail(at, "diag(v) would be " + size_text(m, m) + ": too large");
        return emit(Op::diag_to_matrix, {a}, m, m, double(m) * double(m), at, k);
      }
      const long long len = std::min<long long>(rows(a) - std::max<long long>(0, -k), cols(a) - std::max<long long>(0, k));
      return emit(Op::diag_of_matrix, {a}, std::max<long long>(0, len), 1, flops, at, k);
    }
    if (f == "trace" || f == "inv" || f == "skew" || f == "norm" || f == "transpose") {
      arity(at, 1, 1);
      const int a = expr(nd.kids[0]);
      const double m = double(rows(a)), c = double(cols(a));
      if (f == "transpose") return transposed(emit(Op::transpose, {a}, cols(a), rows(a), m * c, at), a);
      if (f == "norm")
        return emit(Op::norm, {a}, 1, 1, (rows(a) == 1 || cols(a) == 1) ? 2 * m * c : 40.0 * m * c * std::min(m, c), at);
      if (rows(a) != cols(a)) fail(at, f + " needs a square matrix, got " + size_text(rows(a), cols(a)));
      if (f == "trace") return emit(Op::trace, {a}, 1, 1, m, at);
      if (f == "skew") return emit(Op::skew, {a}, rows(a), cols(a), m * m, at);
      return emit(Op::inv, {a}, rows(a), cols(a), 8.0 * m * m * m, at);
    }
    // cross
    arity(at, 2, 2);
    const int a = expr(nd.kids[0]), b = expr(nd.kids[1]);
    const bool three_a = (rows(a) == 3 && cols(a) == 1) || (rows(a) == 1 && cols(a) == 3);
    if (!three_a || rows(a) != rows(b) || cols(a) != cols(b))
      fail(at, "cross needs two vectors of 3 numbers, both rows or both columns; got " + size_text(rows(a), cols(a)) +
                   " and " + size_text(rows(b), cols(b)));
    return emit(Op::cross, {a, b}, rows(a), cols(a), 30, at);
  }

  // Operators, transposes and unary signs chain without bound ((y - y')'' and so on, or y+y+...+y): they are
  // compiled by an explicit stack, post-order, so the depth of C++ recursion is bounded by the parser's nesting
  // limit (calls, brackets, parentheses), not by the program's length.
  static bool chains(NodeKind kind) {
    return kind == NodeKind::binary || kind == NodeKind::unary || kind == NodeKind::transpose;
  }
  int expr(int at) {
    if (!chains(node(at).kind)) return leaf(at);
    struct Pending {
      int at;
      std::size_t next;  // the next operand to compile
    };
    std::vector<Pending> pending{{at, 0}};
    std::vector<int> done;  // the slots of compiled operands, innermost last
    while (!pending.empty()) {
      poll();
      Pending& top = pending.back();
      const Node& nd = node(top.at);
      if (top.next < nd.kids.size()) {
        const int kid = nd.kids[top.next++];
        if (chains(node(kid).kind)) pending.push_back({kid, 0});
        else done.push_back(leaf(kid));
        continue;
      }
      const int a = done[done.size() - nd.kids.size()];
      const int b = nd.kids.size() == 2 ? done.back() : -1;
      done.resize(done.size() - nd.kids.size());
      done.push_back(combine(top.at, a, b));
      pending.pop_back();
    }
    return done.back();
  }

  // A chained node from its operands' slots (b: -1 for one operand).
  int combine(int at, int a, int b) {
    const Node& nd = node(at);
    if (nd.kind == NodeKind::binary) return binary(at, a, b);
    if (nd.kind == NodeKind::transpose)
      return transposed(emit(Op::transpose, {a}, cols(a), rows(a), double(rows(a)) * double(cols(a)), at), a);
    if (nd.text == "+") return a;
    const int out = emit(Op::neg, {a}, rows(a), cols(a), double(rows(a)) * double(cols(a)), at);
    if (varies(a) && !scalar(a)) multiple_[out] = {a, -1.0};
    return out;
  }

  int leaf(int at) {
    const Node& nd = node(at);
    switch (nd.kind) {
      case NodeKind::number: return constant(MatrixXd::Constant(1, 1, nd.value));
      case NodeKind::name: {
        if (auto it = names_.find(nd.text); it != names_.end()) return it->second;
        if (is_function(nd.text)) fail(at, "'" + nd.text + "' is a function: call it with its arguments, as " + nd.text + "(y)");
        fail(at, "undefined variable '" + nd.text + "' (y, t, pi, the parameters and earlier assignments are defined)");
      }
      case NodeKind::end:
        if (ends_.empty()) fail(at, "'end' stands for the last index only inside an index, as in y(end,1)");
        return constant(MatrixXd::Constant(1, 1, double(ends_.back())));
      case NodeKind::colon: fail(at, "':' alone selects everything only as an index, as in y(:,1)");
      case NodeKind::call: return call(at);
      case NodeKind::range: return range(at);
      case NodeKind::matrix: return matrix(at);
      case NodeKind::binary:
      case NodeKind::unary:
      case NodeKind::transpose: return expr(at);
      case NodeKind::assign:
      case NodeKind::row: break;
    }
    fail(at, "unexpected statement");
  }

  // Compiling is work that a request's deadline, its client leaving or a shutdown may cut short: polled per node
  // and per instruction (a folded constant may be a large product).
  static void poll() { throw_if_cancelled(); }

  const Syntax& s_;
  std::unique_ptr<Program> p_;
  std::unordered_map<std::string, int> names_;
  std::unordered_map<std::string, int> shared_;
  std::unordered_map<double, int> numbers_;
  std::unordered_map<int, int> transposed_;                    // slot of x' -> x
  std::unordered_map<int, std::pair<int, double>> multiple_;  // slot of c * x -> (x, c)
  std::vector<Eigen::Index> ends_;
  double cost_ = 0, total_elements_ = 0;
  int at_line_ = 1, at_column_ = 1;
};

Program::Program() : id_(next_program_id.fetch_add(1)) {}
Program::~Program() = default;
std::size_t Program::instructions() const { return code_.size(); }

std::shared_ptr<const Program> compile(std::string_view source, int n, const Parameters& parameters) {
  if (n < 1) fail_at(1, 1, "n must be positive");
  const Syntax syntax = parse(source);
  return Compiler(syntax, n, parameters).run();
}

Eigen::MatrixXd constant_value(std::string_view text, const std::string& field) {
  try {
    return Compiler(parse(text), 1, {}).constant_result();
  } catch (const RequestError& e) {
    if (e.field() != "g") throw;
    throw RequestError(RequestError::Kind::unprocessable, field, field + ": " + e.what(), e.line(), e.column());
  }
}

void check_parameter(const std::string& name, const Eigen::MatrixXd& value) {
  const std::string field = "parameters." + name;
  auto bad = [&](const std::string& message) { throw RequestError(RequestError::Kind::invalid, field, message); };
  bool identifier = !name.empty() && name.size() <= 63 && std::isalpha(static_cast<unsigned char>(name[0]));
  for (char c : name) identifier = identifier && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  if (!identifier) bad(field + ": a parameter's name must be a MATLAB name (a letter, then letters, digits or _)");
  if (name == "y" || name == "t" || name == "end" || name == "g")
    bad(field + ": y, t, g and end are the program's own names");
  if (name == "pi" || is_function(name))
    throw RequestError(RequestError::Kind::unprocessable, field,
                       field + ": '" + name + "' is the language's " + (name == "pi" ? "constant" : "function") +
                           " of that name; a parameter may not hide it (choose another name)");
  if (double(value.size()) > kMaxElements) bad(field + " is too large");
  if (!value.allFinite()) bad(field + " must have finite entries");
}

void Program::prepare(Workspace& ws) const {
  ws.id = id_;
  ws.time.reset();
  ws.holds_y = ws.holds_derivatives = false;
  ws.stacked_k = -1;
  ws.stacked.clear();
  const std::size_t slots = rows_.size();
  ws.val.assign(slots, MatrixXd());
  ws.tan.assign(slots, MatrixXd());
  ws.aux.assign(slots, MatrixXd());
  for (std::size_t s = 0; s < slots; ++s) {
    if (varies_[s]) ws.tan[s] = MatrixXd::Zero(rows_[s], cols_[s]);
    if (varies_[s] || timed_[s]) ws.val[s].resize(rows_[s], cols_[s]);
  }
  // The slots are never resized again, so the instructions' operands are bound to them once.
  const auto bind = [&](const std::vector<Instruction>& code, std::vector<Bound>& out) {
    out.clear();
    for (const Instruction& ins : code) {
      Bound b;
      for (int i : ins.in) {
        const auto s = static_cast<std::size_t>(i);
        b.x.push_back(varies_[s] || timed_[s] ? &ws.val[s] : &constant_[s]);
        // The values of t alone take no tangents.
        const auto zero = zeros_.find({rows_[s], cols_[s]});
        b.dx.push_back(varies_[s] ? &ws.tan[s] : zero == zeros_.end() ? nullptr : &zero->second);
      }
      const auto o = static_cast<std::size_t>(ins.out);
      b.out = &ws.val[o];
      b.dout = &ws.tan[o];
      b.aux = &ws.aux[o];
      out.push_back(std::move(b));
    }
  };
  bind(code_, ws.code);
  bind(time_code_, ws.time_code);
}

namespace {
// One per thread, shared by every kind of evaluation (a thread_local inside with_workspace would be one per
// lambda type, so that g and dg_y at the same y would not find each other's values).
Program::Workspace& thread_workspace() {
  thread_local Program::Workspace cached;
  return cached;
}
}  // namespace

// A small program's slots are sized once per thread and kept, so its evaluations allocate nothing; a large one's
// are sized per call and freed after it.
template <class F>
void Program::with_workspace(F&& f) const {
  if (elements_ > kMaxCachedElements) {
    Workspace local;
    prepare(local);
    f(local);
    return;
  }
  Workspace& cached = thread_workspace();
  if (cached.id != id_) prepare(cached);
  f(cached);
}

namespace {
// a and b hold the same numbers, bit for bit (-0 is not 0, a NaN is itself).
bool same_bits(const MatrixXd& a, const Program::In& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) return false;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      if (std::bit_cast<std::uint64_t>(a(i, j)) != std::bit_cast<std::uint64_t>(b(i, j))) return false;
  return true;
}
}  // namespace

void Program::run(const In& y, double t, const In* dy, Workspace& ws) const {
  if (cancellation_requested()) throw Cancelled{};
  const auto ys = static_cast<std::size_t>(y_slot_);
  // Newton asks for g(y) and then for dg_y at the same y (one direction or a basis of them): the values of the
  // last y are kept, and a call at that y forms its tangents only.
  const bool known = ws.holds_y && ws.time == t && same_bits(ws.val[ys], y);
  if (!known) {
    ws.holds_y = false;  // until this pass has run through
    if (ws.time != t) {  // the values of t alone, once per time (an integrator's stage)
      ws.val[static_cast<std::size_t>(t_slot_)](0, 0) = t;
      for (std::size_t i = 0; i < time_code_.size(); ++i) {
        const Bound& b = ws.time_code[i];
        apply(time_code_[i], b.x, *b.out, nullptr, nullptr, *b.aux);
      }
      ws.time = t;
    }
    ws.val[ys] = y;
  } else if (dy && !ws.holds_derivatives) {  // the values came from g alone
    form_derivatives(ws);
  }
  if (known && !dy) return;
  if (dy) ws.tan[ys] = *dy;
  for (std::size_t i = 0; i < code_.size(); ++i) {
    const Bound& b = ws.code[i];
    apply(code_[i], b.x, *b.out, dy ? &b.dx : nullptr, dy ? b.dout : nullptr, *b.aux, known);
  }
  if (!known) {
    ws.holds_y = true;
    ws.holds_derivatives = dy != nullptr;
  }
}

// f'(a) of the entrywise functions at the values held, for the tangents (sin's and cos's came with the values).
void Program::form_derivatives(Workspace& ws) const {
  for (std::size_t i = 0; i < code_.size(); ++i)
    if (code_[i].op == Op::fn && !forms_derivative_with_value(code_[i].fn))
      derivative_fn(code_[i].fn, *ws.code[i].x[0], *ws.code[i].out, *ws.code[i].aux);
  ws.holds_derivatives = true;
}

namespace {
// Direction d's tangent in a stacked matrix of tangents ((rows k) x cols).
Eigen::Map<MatrixXd, 0, Eigen::OuterStride<>> stacked_direction(MatrixXd& stacked, Eigen::Index rows, Eigen::Index d) {
  // An empty value's tangents have no storage: no offset from its null data.
  double* const data = stacked.size() == 0 ? stacked.data() : stacked.data() + rows * d;
  return {data, rows, stacked.cols(), Eigen::OuterStride<>(stacked.rows())};
}
// The same memory as rows x (k cols), direction d's column j in column d + k j: a product from the left by a
// value is one product of this wide matrix, as a product from the right is one of the stacked one.
Eigen::Map<MatrixXd> side_by_side(MatrixXd& stacked, Eigen::Index rows, Eigen::Index k) {
  return {stacked.data(), rows, stacked.cols() * k};  // k directions of an empty value are still k blocks wide
}
}  // namespace

// Instruction i's tangents along all k directions from its operands' (values and f'(a) held): the product rules
// of the common operations on the stacked matrices at once, the others one direction at a time.
void Program::tangents_along(std::size_t i, Eigen::Index k, Workspace& ws) const {
  const Instruction& ins = code_[i];
  const Bound& b = ws.code[i];
  const auto slot = [&](std::size_t j) { return static_cast<std::size_t>(ins.in[j]); };
  const auto varies = [&](std::size_t j) { return bool(varies_[slot(j)]); };
  const auto dx = [&](std::size_t j) -> MatrixXd& { return ws.stacked[slot(j)]; };
  const auto o = static_cast<std::size_t>(ins.out);
  MatrixXd& out = ws.stacked[o];
  const Eigen::Index r = rows_[o], c = cols_[o];
  bool same_shape = true;  // no operand spreads a 1x1 over the other
  for (std::size_t j = 0; j < ins.in.size(); ++j) same_shape = same_shape && rows_[slot(j)] == r && cols_[slot(j)] == c;
  // alpha dA + beta dB, a term left out where its operand is constant
  const auto combination = [&](double alpha, double beta) {
    if (varies(0) && varies(1)) out = alpha * dx(0) + beta * dx(1);
    else if (varies(0)) out = alpha * dx(0);
    else out = beta * dx(1);
  };
  switch (ins.op) {
    case Op::add: if (same_shape) return combination(1, 1); break;
    case Op::sub: if (same_shape) return combination(1, -1); break;
    case Op::axpby: if (same_shape) return combination(ins.alpha, ins.beta); break;
    case Op::neg: out = -dx(0); return;
    case Op::transpose: case Op::antisym: case Op::skew:
      for (Eigen::Index d = 0; d < k; ++d) {
        const auto a = stacked_direction(dx(0), rows_[slot(0)], d);
        auto t = stacked_direction(out, r, d);
        if (ins.op == Op::transpose) t = a.transpose();
        else if (ins.op == Op::antisym) t = a - a.transpose();
        else t = 0.5 * (a - a.transpose());
      }
      return;
    case Op::matmul:  // (AB)' = A'B + AB'
      if (is_scalar(*b.x[0]) || is_scalar(*b.x[1])) break;
      if (varies(0)) out.noalias() = dx(0) * *b.x[1];
      else out.setZero();
      if (varies(1)) side_by_side(out, r, k).noalias() += *b.x[0] * side_by_side(dx(1), rows_[slot(1)], k);
      return;
    case Op::emul:  // (A .* B)' = A' .* B + A .* B'
      if (!same_shape) break;
      if (varies(0)) out = (dx(0).array() * b.x[1]->replicate(k, 1).array()).matrix();
      else out.setZero();
      if (varies(1)) out.array() += b.x[0]->replicate(k, 1).array() * dx(1).array();
      return;
    case Op::fn: out = (b.aux->replicate(k, 1).array() * dx(0).array()).matrix(); return;
    default: break;
  }
  ws.scratch.resize(ins.in.size());
  ws.scratch_dx.resize(ins.in.size());
  for (Eigen::Index d = 0; d < k; ++d) {
    for (std::size_t j = 0; j < ins.in.size(); ++j) {
      if (!varies(j)) {
        ws.scratch_dx[j] = b.dx[j];  // zero
        continue;
      }
      ws.scratch[j] = stacked_direction(dx(j), rows_[slot(j)], d);
      ws.scratch_dx[j] = &ws.scratch[j];
    }
    ws.scratch_out.resize(r, c);
    apply(ins, b.x, *b.out, &ws.scratch_dx, &ws.scratch_out, *b.aux, true);
    stacked_direction(out, r, d) = ws.scratch_out;
  }
}

const MatrixXd& Program::tangent(const Workspace& ws, std::size_t s) const {
  return varies_[s] ? ws.tan[s] : zeros_.at({rows_[s], cols_[s]});
}

double Program::varying_elements() const {
  double varying = 0;
  for (std::size_t s = 0; s < rows_.size(); ++s)
    if (varies_[s]) varying += double(rows_[s]) * double(cols_[s]);
  return varying;
}

Eigen::Index Program::directions_per_pass(Eigen::Index k) const {
  const double varying = varying_elements();
  if (varying == 0 || k <= 1) return std::max<Eigen::Index>(k, 1);
  return std::clamp<Eigen::Index>(static_cast<Eigen::Index>(kMaxStackedElements / varying), 1, k);
}

double Program::workspace_bytes(int directions) const {
  double entries = 0, largest = 0;
  for (std::size_t s = 0; s < rows_.size(); ++s) {
    const double size = double(rows_[s]) * double(cols_[s]);
    if (varies_[s] || timed_[s]) entries += size;
    largest = std::max(largest, size);
  }
  const double varying = varying_elements();
  entries += varying;  // the tangents
  const auto size_of = [&](int s) { return double(rows_[static_cast<std::size_t>(s)]) * double(cols_[static_cast<std::size_t>(s)]); };
  for (const std::vector<Instruction>* code : {&code_, &time_code_})
    for (const Instruction& ins : *code) {
      if (ins.op == Op::fn) entries += size_of(ins.out);
      if (ins.op == Op::left_div) entries += size_of(ins.in[0]);
      if (ins.op == Op::right_div) entries += size_of(ins.in[1]);
    }
  const double stacked = varying * double(directions_per_pass(std::max(directions, 1)));
  const double square = double(n_) * double(n_);
  // one pass's stacked tangents (none when a direction goes alone), one direction's scratch, the caller's matrices
  entries += (stacked <= kMaxStackedElements ? stacked : 0) + largest + 4 * square;
  return entries * double(sizeof(double));
}

// The value of slot r after a run.
const MatrixXd& Program::result(const Workspace& ws) const {
  const auto r = static_cast<std::size_t>(result_);
  return varies_[r] || timed_[r] ? ws.val[r] : constant_[r];
}

void Program::eval(const In& y, double t, MatrixXd& g) const {
  with_workspace([&](Workspace& ws) {
    run(y, t, nullptr, ws);
    g = result(ws);
  });
}

void Program::eval_with_tangent(const In& y, double t, const In& dy, MatrixXd& g, MatrixXd& dg) const {
  with_workspace([&](Workspace& ws) {
    run(y, t, &dy, ws);
    g = result(ws);
    dg = tangent(ws, static_cast<std::size_t>(result_));
  });
}

void Program::eval_along(const In& y, double t, Eigen::Index k, const Direction& direction,
                         const Derivative& derivative) const {
  const Eigen::Index n = n_, per_pass = directions_per_pass(k);
  const auto ys = static_cast<std::size_t>(y_slot_), r = static_cast<std::size_t>(result_);
  with_workspace([&](Workspace& ws) {
    MatrixXd dy(n, n), dg(n, n);
    for (Eigen::Index first = 0; first < k; first += per_pass) {
      const Eigen::Index passing = std::min(per_pass, k - first);
      if (ws.stacked_k != passing) {
        ws.stacked_fits = varying_elements() * double(passing) <= kMaxStackedElements;
        ws.stacked.assign(rows_.size(), MatrixXd());
        if (ws.stacked_fits)
          for (std::size_t s = 0; s < rows_.size(); ++s)
            if (varies_[s]) ws.stacked[s].resize(rows_[s] * passing, cols_[s]);
        ws.stacked_k = passing;
      }
      if (!ws.stacked_fits) {  // one direction at a time: the values once, the later directions find them kept
        for (Eigen::Index d = first; d < first + passing; ++d) {
          direction(d, dy);
          const In in(dy);
          run(y, t, &in, ws);
          derivative(d, tangent(ws, r));
        }
        continue;
      }
      run(y, t, nullptr, ws);
      if (!ws.holds_derivatives) form_derivatives(ws);
      for (Eigen::Index d = 0; d < passing; ++d) {
        direction(first + d, dy);
        if (varies_[ys]) stacked_direction(ws.stacked[ys], n, d) = dy;
      }
      for (std::size_t i = 0; i < code_.size(); ++i) {
        if (cancellation_requested()) throw Cancelled{};
        tangents_along(i, passing, ws);
      }
      for (Eigen::Index d = 0; d < passing; ++d) {
        if (varies_[r]) dg = stacked_direction(ws.stacked[r], n, d);
        else dg.setZero(n, n);  // g does not depend on y
        derivative(first + d, dg);
      }
    }
    // A thread keeps no more between requests than a small program's own workspace.
    if (varying_elements() * double(ws.stacked_k) > kMaxCachedElements) {
      ws.stacked.clear();
      ws.stacked_k = -1;
    }
  });
}

void Program::eval_along(const In& y, double t, const In& dys, MatrixXd& dgs) const {
  const Eigen::Index n = n_, k = dys.rows() / n;
  dgs.resize(n * k, n);
  eval_along(
      y, t, k, [&](Eigen::Index d, MatrixXd& dy) { dy = dys.middleRows(d * n, n); },
      [&](Eigen::Index d, const MatrixXd& dg) { dgs.middleRows(d * n, n) = dg; });
}

}  // namespace lienewton::user_field
