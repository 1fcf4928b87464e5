// The core's closed-form groups for lienewton.groups: SO(3), SE(3) and SO(n), each function applied to a stack of
// elements (an (m, k) array of algebra coordinates or an (m, d, d) array of matrices) in one call, so that the
// Python classes are vectorised like scipy's Rotation and compute exactly what the solvers compute.
#include "python/group_bindings.hpp"

#include <pybind11/numpy.h>

#include <string>

#include "core/groups/se3.hpp"
#include "core/groups/so3.hpp"
#include "core/groups/son.hpp"

namespace py = pybind11;

namespace lienewton::python {

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The rows of a (m, k) array; refuses any other shape.
void expect_shape(const Array& a, std::initializer_list<py::ssize_t> tail, const char* what) {
  bool ok = a.ndim() == static_cast<py::ssize_t>(tail.size()) + 1;
  for (std::size_t i = 0; ok && i < tail.size(); ++i) ok = a.shape(static_cast<py::ssize_t>(i) + 1) == tail.begin()[i];
  if (ok) return;
  std::string want = "(m";
  for (py::ssize_t d : tail) want += ", " + std::to_string(d);
  throw py::value_error(std::string(what) + " must be an array of shape " + want + ")");
}

// out[i] = f(in[i]) over the stack: In and Out are fixed- or dynamic-size Eigen types mapped row-major onto the
// arrays' rows (a matrix in a NumPy array is row-major; Eigen's default is column-major).
template <class In, class Out, class F>
Array map_stack(const Array& in, py::ssize_t in_rows, py::ssize_t in_cols, py::ssize_t out_rows, py::ssize_t out_cols,
                bool out_is_vector, F f) {
  using InMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const py::ssize_t m = in.shape(0);
  Array out = out_is_vector ? Array({m, out_rows}) : Array({m, out_rows, out_cols});
  const double* src = in.data();
  double* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < m; ++i) {
      const In x = Eigen::Map<const InMat>(src + i * in_rows * in_cols, in_rows, in_cols);
      Eigen::Map<InMat>(dst + i * out_rows * out_cols, out_rows, out_cols) = f(x);
    }
  }
  return out;
}

}  // namespace

void bind_groups(py::module_& m) {
  using so3::Mat;
  using so3::Vec;
  using Vec6 = se3::Vec6;
  using Mat4 = se3::Mat4;
  using Mat6 = se3::Mat6;
  // std::domain_error (LogDomainError: not a rotation, or an angle at pi) becomes ValueError.
  m.def("so3_exp", [](const Array& w) {
    expect_shape(w, {3}, "w");
    return map_stack<Vec, Mat>(w, 3, 1, 3, 3, false, [](const Vec& v) { return so3::exp(v); });
  });
  m.def("so3_log", [](const Array& r) {
    expect_shape(r, {3, 3}, "R");
    return map_stack<Mat, Vec>(r, 3, 3, 3, 1, true, [](const Mat& x) { return so3::checked_log(x); });
  });
  m.def("so3_dexp", [](const Array& w) {
    expect_shape(w, {3}, "w");
    return map_stack<Vec, Mat>(w, 3, 1, 3, 3, false, [](const Vec& v) { return so3::dexp_matrix(v); });
  });
  m.def("so3_dexpinv", [](const Array& w) {
    expect_shape(w, {3}, "w");
    return map_stack<Vec, Mat>(w, 3, 1, 3, 3, false, [](const Vec& v) { return so3::dexpinv_matrix(v); });
  });
  m.def("se3_exp", [](const Array& xi) {
    expect_shape(xi, {6}, "xi");
    return map_stack<Vec6, Mat4>(xi, 6, 1, 4, 4, false, [](const Vec6& v) { return se3::exp(v); });
  });
  m.def("se3_log", [](const Array& t) {
    expect_shape(t, {4, 4}, "T");
    return map_stack<Mat4, Vec6>(t, 4, 4, 6, 1, true, [](const Mat4& x) { return se3::checked_log(x); });
  });
  m.def("se3_dexp", [](const Array& xi) {
    expect_shape(xi, {6}, "xi");
    return map_stack<Vec6, Mat6>(xi, 6, 1, 6, 6, false, [](const Vec6& v) { return se3::dexp_matrix(v); });
  });
  m.def("se3_dexpinv", [](const Array& xi) {
    expect_shape(xi, {6}, "xi");
    return map_stack<Vec6, Mat6>(xi, 6, 1, 6, 6, false, [](const Vec6& v) { return se3::dexpinv_matrix(v); });
  });
  // SO(n) on the paper's coordinates (son.hpp's basis E_ij - E_ji, i < j, row-major), q = n(n-1)/2.
  const auto q_of = [](int n) {
    if (n < 2) throw py::value_error("SO(n) needs n >= 2");
    return static_cast<py::ssize_t>(son::algebra_dim(n));
  };
  m.def("son_hat", [q_of](const Array& a, int n) {
    const py::ssize_t q = q_of(n);
    expect_shape(a, {q}, "alpha");
    return map_stack<son::Vec, son::Mat>(a, q, 1, n, n, false, [n](const son::Vec& v) { return son::hat(v, n); });
  });
  m.def("son_vee", [q_of](const Array& v, int n) {
    const py::ssize_t q = q_of(n);
    expect_shape(v, {n, n}, "X");
    return map_stack<son::Mat, son::Vec>(v, n, n, q, 1, true, [](const son::Mat& x) { return son::vee(x); });
  });
  m.def("son_exp", [q_of](const Array& a, int n) {
    const py::ssize_t q = q_of(n);
    expect_shape(a, {q}, "alpha");
    return map_stack<son::Vec, son::Mat>(a, q, 1, n, n, false,
                                         [n](const son::Vec& v) { return son::exp(son::hat(v, n)); });
  });
  m.def("son_log", [q_of](const Array& r, int n) {
    const py::ssize_t q = q_of(n);
    expect_shape(r, {n, n}, "R");
    return map_stack<son::Mat, son::Vec>(r, n, n, q, 1, true, [](const son::Mat& x) { return son::vee(son::log(x)); });
  });
  m.def("son_dexp", [q_of](const Array& a, int n) {
    const py::ssize_t q = q_of(n);
    expect_shape(a, {q}, "alpha");
    return map_stack<son::Vec, son::Mat>(a, q, 1, q, q, false, [n](const son::Vec& v) {
      return son::dexp_matrix(son::spectral_form_of_skew(son::hat(v, n)));
    });
  });
  m.def("son_dexpinv", [q_of](const Array& a, int n) {
    const py::ssize_t q = q_of(n);
    expect_shape(a, {q}, "alpha");
    return map_stack<son::Vec, son::Mat>(a, q, 1, q, q, false, [n](const son::Vec& v) {
      return son::dexpinv_matrix(son::spectral_form_of_skew(son::hat(v, n)));
    });
  });
}

}  // namespace lienewton::python
