#include "son.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "bernoulli.hpp"

namespace lienewton::son {
namespace {


// Reads the real Schur form T of a normal matrix: blocks of size 1 or 2 along the diagonal. The angle of a
// 2x2 block [a b; c d] is atan2((c - b)/2, (a + d)/2) for a rotation and (c - b)/2 for a skew matrix: the
// block is, to rounding, rot(theta) resp. theta J, whatever standardisation Eigen chose.
template <class AngleOfBlock>
std::vector<SpectralForm::Block> read_blocks(const Mat& t, AngleOfBlock angle_of) {
  std::vector<SpectralForm::Block> blocks;
  const int n = static_cast<int>(t.rows());
  for (int i = 0; i < n;) {
    if (i + 1 < n && t(i + 1, i) != 0.0) {
      blocks.push_back({i, 2, angle_of(t(i, i), t(i, i + 1), t(i + 1, i), t(i + 1, i + 1))});
      i += 2;
    } else {
      blocks.push_back({i, 1, 0.0});
      i += 1;
    }
  }
  return blocks;
}

Eigen::Matrix2d rotation2(double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

// F(ad_v) for an analytic F, given its values F(i w) = re(w) + i im(w) on the imaginary axis (where the
// eigenvalue differences of a skew v lie). In Q's basis, block (k,l) of X = Q^T U Q is mapped by
// X -> A_k X - X A_l with A = theta J; J behaves like i, so
//   2x2: the part of X commuting with J sees w = theta_k - theta_l, the anticommuting part w = theta_k + theta_l;
//   2x1: w = theta_k; 1x2: w = theta_l (acting on the transposed row); 1x1: w = 0.
// The values of F are tabulated once per block pair, then applied to as many X as needed.
class AdFunction {
 public:
  template <class F>
  AdFunction(const SpectralForm& s, F f) : s_(s), nb_(s.blocks.size()), minus_(nb_ * nb_), plus_(nb_ * nb_) {
    for (std::size_t k = 0; k < nb_; ++k)
      for (std::size_t l = 0; l < nb_; ++l) {
        const auto& bk = s.blocks[k];
        const auto& bl = s.blocks[l];
        const double w_minus = bk.size == 2 ? (bl.size == 2 ? bk.theta - bl.theta : bk.theta) : bl.theta;
        minus_[k * nb_ + l] = f(w_minus);
        plus_[k * nb_ + l] = f(bk.theta + bl.theta);
      }
  }

  // X (in Q's basis) -> F(ad) X, in place, block pair by block pair.
  void apply_in_q_basis(Mat& x) const {
    for (std::size_t k = 0; k < nb_; ++k)
      for (std::size_t l = 0; l < nb_; ++l) {
        const Entries e = entries(k, l);
        double m[4];
        for (int i = 0; i < e.count; ++i) m[i] = x(e.row[i], e.col[i]);
        map_block(k, l, m);
        for (int i = 0; i < e.count; ++i) x(e.row[i], e.col[i]) = m[i];
      }
  }

  Mat apply(const Mat& u) const {
    Mat x = s_.q.transpose() * u * s_.q;
    apply_in_q_basis(x);
    Mat r = s_.q * x * s_.q.transpose();
    return 0.5 * (r - r.transpose());
  }

  // P and F(ad_v) P (son.hpp). Column (ij) of P is vee(Q b Q^T) for b = E_ij - E_ji, i.e. entries
  // Q_ai Q_bj - Q_aj Q_bi at a < b; in Q's basis F(ad) couples only the coordinates of one block pair (at most 4),
  // so column e of F(ad) P = P Psi (Psi: F(ad) on Q's coordinates) combines at most 4 columns of P. O(q^2).
  SpectralBasis in_spectral_basis() const {
    const Mat& q = s_.q;
    const int n = static_cast<int>(q.rows()), dim = algebra_dim(n);
    SpectralBasis out{Mat(dim, dim), Mat::Zero(dim, dim)};
    for (int i = 0, col = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j, ++col)
        for (int a = 0, row = 0; a + 1 < n; row += n - 1 - a, ++a)
          out.basis.col(col).segment(row, n - 1 - a) =
              q(a, i) * q.col(j).tail(n - 1 - a) - q(a, j) * q.col(i).tail(n - 1 - a);
    const auto index = [n](int i, int j) { return i * (2 * n - i - 1) / 2 + (j - i - 1); };
    for (std::size_t k = 0; k < nb_; ++k)
      for (std::size_t l = k; l < nb_; ++l) {
        const Entries e = entries(k, l);
        if (k == l) {  // a 2x2 diagonal block [0 x; -x 0] of a skew X: coordinate (r, r + 1) alone
          if (e.count < 4) continue;
          double m[4] = {0.0, 1.0, -1.0, 0.0};
          map_block(k, l, m);
          const int c = index(e.row[1], e.col[1]);
          out.times_basis.col(c) = m[1] * out.basis.col(c);
          continue;
        }
        for (int from = 0; from < e.count; ++from) {  // column `from` of the block's map, onto P's columns
          double m[4] = {0.0, 0.0, 0.0, 0.0};
          m[from] = 1.0;
          map_block(k, l, m);
          auto target = out.times_basis.col(index(e.row[from], e.col[from]));
          for (int to = 0; to < e.count; ++to)
            if (m[to] != 0.0) target += m[to] * out.basis.col(index(e.row[to], e.col[to]));
        }
      }
    return out;
  }

 private:
  // The entries of block pair (k, l) in X, in the order (r, c), (r, c + 1), (r + 1, c), (r + 1, c + 1) of those
  // the block sizes have.
  struct Entries {
    int count = 0;
    int row[4], col[4];
  };
  Entries entries(std::size_t k, std::size_t l) const {
    const auto& bk = s_.blocks[k];
    const auto& bl = s_.blocks[l];
    Entries e;
    for (int i = 0; i < bk.size; ++i)
      for (int j = 0; j < bl.size; ++j, ++e.count) {
        e.row[e.count] = bk.start + i;
        e.col[e.count] = bl.start + j;
      }
    return e;
  }

  // F(ad) on block pair (k, l), its entries m in the order of entries(k, l). Scalar code (J only permutes the
  // entries and flips signs): small Eigen blocks cost more than the arithmetic.
  void map_block(std::size_t k, std::size_t l, double* m) const {
    const auto& bk = s_.blocks[k];
    const auto& bl = s_.blocks[l];
    const std::complex<double> fm = minus_[k * nb_ + l];
    if (bk.size == 2 && bl.size == 2) {
      // m = a + b with a = (m - J m J)/2 commuting with J (sees F(i(theta_k - theta_l))) and b = (m + J m J)/2
      // anticommuting (F(i(theta_k + theta_l))); J m J = [-m11 m10; m01 -m00].
      const double m00 = m[0], m01 = m[1], m10 = m[2], m11 = m[3];
      const double a00 = 0.5 * (m00 + m11), a01 = 0.5 * (m01 - m10), a10 = 0.5 * (m10 - m01), a11 = 0.5 * (m11 + m00);
      const double b00 = 0.5 * (m00 - m11), b01 = 0.5 * (m01 + m10), b10 = 0.5 * (m10 + m01), b11 = 0.5 * (m11 - m00);
      const std::complex<double> fp = plus_[k * nb_ + l];
      // F X = re X + im J X per part, J [u00 u01; u10 u11] = [-u10 -u11; u00 u01].
      m[0] = (fm.real() * a00 + fm.imag() * -a10) + (fp.real() * b00 + fp.imag() * -b10);
      m[1] = (fm.real() * a01 + fm.imag() * -a11) + (fp.real() * b01 + fp.imag() * -b11);
      m[2] = (fm.real() * a10 + fm.imag() * a00) + (fp.real() * b10 + fp.imag() * b00);
      m[3] = (fm.real() * a11 + fm.imag() * a01) + (fp.real() * b11 + fp.imag() * b01);
    } else if (bk.size == 2 || bl.size == 2) {  // a column pair [u0; u1] -> re u + im J u (a row pair: transposed)
      const double u0 = m[0], u1 = m[1];
      m[0] = fm.real() * u0 + fm.imag() * -u1;
      m[1] = fm.real() * u1 + fm.imag() * u0;
    } else {
      m[0] *= fm.real();
    }
  }

  const SpectralForm& s_;
  std::size_t nb_;
  std::vector<std::complex<double>> minus_, plus_;
};

// phi(x) = (1 - e^-x)/x at x = i w: sin(w)/w - i (1 - cos w)/w   (dexp, (2.10))
std::complex<double> dexp_function(double w) {
  if (w == 0.0) return {1.0, 0.0};
  const double s = std::sin(0.5 * w);
  return {std::sin(w) / w, -2.0 * s * s / w};
}

// psi(x) = x / (1 - e^-x) at x = i w: (w/2) cot(w/2) + i w/2   (dexpinv, (3.9))
std::complex<double> dexpinv_function(double w) {
  if (w == 0.0) return {1.0, 0.0};
  return {0.5 * w / std::tan(0.5 * w), 0.5 * w};
}

}  // namespace

Mat hat(const Vec& alpha, int n) {
  Mat m = Mat::Zero(n, n);
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j, ++k) {
      m(i, j) = alpha(k);
      m(j, i) = -alpha(k);
    }
  return m;
}

Vec vee(const Mat& m) {
  const int n = static_cast<int>(m.rows());
  Vec a(algebra_dim(n));
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j, ++k) a(k) = 0.5 * (m(i, j) - m(j, i));
  return a;
}

double SpectralForm::max_angle() const {
  double m = 0.0;
  for (const auto& b : blocks) m = std::max(m, std::abs(b.theta));
  return m;
}

Mat SpectralForm::skew() const {
  if (accurate_skew.size() > 0) return accurate_skew;
  const int n = static_cast<int>(q.rows());
  Mat l = Mat::Zero(n, n);
  for (const auto& b : blocks)
    if (b.size == 2) {
      l(b.start, b.start + 1) = -b.theta;
      l(b.start + 1, b.start) = b.theta;
    }
  Mat v = q * l * q.transpose();
  return 0.5 * (v - v.transpose());
}

namespace {
// blockdiag(rot theta, 1) - I, with cos - 1 = -2 sin^2(theta/2) free of cancellation.
Mat rotation_minus_identity(const SpectralForm& s) {
  const int n = static_cast<int>(s.q.rows());
  Mat d = Mat::Zero(n, n);
  for (const auto& b : s.blocks)
    if (b.size == 2) {
      const double h = std::sin(0.5 * b.theta);
      d.block<2, 2>(b.start, b.start) = rotation2(b.theta);
      d(b.start, b.start) = d(b.start + 1, b.start + 1) = -2.0 * h * h;
    }
  return d;
}
}  // namespace

Mat SpectralForm::rotation() const {
  const int n = static_cast<int>(q.rows());
  return Mat::Identity(n, n) + q * rotation_minus_identity(*this) * q.transpose();
}

SpectralForm spectral_form_of_skew(const Mat& v) {
  Eigen::RealSchur<Mat> schur(v);
  SpectralForm s;
  s.q = schur.matrixU();
  s.blocks = read_blocks(schur.matrixT(), [](double, double b, double c, double) { return 0.5 * (c - b); });
  return s;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Below this cosine (angles above 3pi/4) F(c) = acos(c)/sqrt(1 - c^2) grows too steep; use the Schur form.
constexpr double kSymmetricLogMinCos = -0.7;

void check_orthogonal(const Mat& r, double orthogonality_tol) {
  if (r.rows() != r.cols() || r.rows() < 2) throw LogDomainError("log needs a square matrix of size >= 2", kNaN);
  if (!r.allFinite()) throw LogDomainError("log of a matrix with non-finite entries", kNaN);
  const int n = static_cast<int>(r.rows());
  const double orth = (r.transpose() * r - Mat::Identity(n, n)).norm();
  if (!(orth <= orthogonality_tol)) throw LogDomainError("log of a matrix that is not orthogonal", kNaN);
}

// F(c) = acos(c) / sqrt(1 - c^2) = t / sin t; near c = 1 its series in d = 1 - c (the direct form is 0/0).
double angle_over_sine(double c) {
  const double d = 1.0 - c;
  if (std::abs(d) < 1e-3) return 1.0 + d * (1.0 / 3 + d * (2.0 / 15 + d * (4.0 / 70 + d * (8.0 / 315))));
  return std::acos(c) / std::sqrt(d * (1.0 + c));
}

// The Schur form of a rotation: Q, the angles, and the checks of log's domain (det -1, an angle within margin of
// pi). Throws LogDomainError.
SpectralForm schur_form_of_rotation(const Mat& r, double margin) {
  Eigen::RealSchur<Mat> schur(r);
  const Mat& t = schur.matrixT();
  SpectralForm s;
  s.q = schur.matrixU();
  s.blocks = read_blocks(t, [](double a, double b, double c, double d) {
    return std::atan2(0.5 * (c - b), 0.5 * (a + d));
  });
  int minus_ones = 0;
  for (const auto& b : s.blocks)
    if (b.size == 1 && t(b.start, b.start) < 0.0) ++minus_ones;
  if (minus_ones % 2 == 1) throw LogDomainError("log of a matrix with determinant -1 (not in SO(N))", kNaN);
  const double angle = minus_ones > 0 ? std::numbers::pi : s.max_angle();
  if (angle > std::numbers::pi - margin)
    throw LogDomainError("log undefined: rotation angle " + std::to_string(angle) + " is at pi", angle);
  return s;
}

// Above this cosine of the largest angle (angles below ~0.14) the angle is read from ||log R||_2 (see below).
constexpr double kAngleFromNormMinCos = 0.99;

// log R = F(S) A (see son.hpp) on the eigenvectors of S with angles up to 3pi/4, one symmetric eigensolve.
// The eigenvectors with larger angles (cosines below kSymmetricLogMinCos, where F is steep) span an invariant
// subspace W of R, in pairs; with far_planes the k x k rotation W^T R W (k = 2 for one such plane) is logged by
// its Schur form, which reads those angles to absolute accuracy eps, and the domain checks run there.
// Nothing when an angle exceeds 3pi/4 and !far_planes, or when W is not invariant (a cluster split at the
// threshold): the caller then takes the Schur form of all of R. Throws LogDomainError (det -1, angle at pi).
std::optional<Mat> log_from_symmetric_part(const Mat& r, bool far_planes, double* max_angle) {
  const int n = static_cast<int>(r.rows());
  const Mat a = 0.5 * (r - r.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat> eig(0.5 * (r + r.transpose()));
  const Vec& c = eig.eigenvalues();  // ascending: the largest angles first
  const Mat& v = eig.eigenvectors();
  int k = 0;
  while (k < n && c(k) < kSymmetricLogMinCos) ++k;
  if (k > 0 && !far_planes) return std::nullopt;
  if (k % 2 == 1) {  // a plane's two equal cosines straddle the threshold, or det R = -1 (an eigenvalue -1 alone)
    if (k < n && c(k) - c(k - 1) < 1e-6) ++k;
    else throw LogDomainError("log of a matrix with determinant -1 (not in SO(N))", kNaN);
  }
  const Mat b = v.transpose() * a;  // row i is -(A v_i)^T: its norm is the sine of v_i's angle
  const Vec f = c.tail(n - k).unaryExpr([](double x) { return angle_over_sine(x); });
  Mat l = v.rightCols(n - k) * f.asDiagonal() * b.bottomRows(n - k);
  double angle = 0.0;
  if (k > 0) {
    const auto w = v.leftCols(k);
    const Mat rw = w.transpose() * r * w;
    if (!((rw.transpose() * rw - Mat::Identity(k, k)).norm() <= 1e-8)) return std::nullopt;
    const SpectralForm far = schur_form_of_rotation(rw, kLogDomainMargin);
    l.noalias() += w * far.skew() * w.transpose();
    angle = far.max_angle();
  } else if (c(0) < kAngleFromNormMinCos) {
    // sin = ||A v_0|| (first-order insensitive to v_0's rounding: A^2 = S^2 - I keeps S's eigenspaces).
    angle = std::atan2(b.row(0).norm(), c(0));
  } else {
    // acos of a cosine near 1 has absolute error sqrt(eps) (2.98e-8 at angle 1e-16), and for tiny angles S's
    // eigenvectors are any basis: the angle is read from log itself, ||L||_2 = max theta, with L's relative
    // accuracy.
    l = (0.5 * (l - l.transpose())).eval();
    if (max_angle) {
      const Eigen::SelfAdjointEigenSolver<Mat> ltl(l.transpose() * l, Eigen::EigenvaluesOnly);
      *max_angle = std::sqrt(std::max(0.0, ltl.eigenvalues().maxCoeff()));
    }
    return l;
  }
  if (max_angle) *max_angle = angle;
  return (0.5 * (l - l.transpose())).eval();
}

// Degrees m of the Pade approximants r_m(x) = p_m(x) / p_m(-x) to e^x and the largest |x| at which each keeps
// the relative backward error below eps (Higham, SIAM J. Matrix Anal. Appl. 26 (2005), Table 2.3).
struct PadeDegree {
  int m;
  double theta;
};
constexpr PadeDegree kPadeDegrees[] = {{3, 1.495585217958292e-2},
                                       {5, 2.539398330063230e-1},
                                       {7, 9.504178996162932e-1},
                                       {9, 2.097847961257068e0},
                                       {13, 5.371920351148152e0}};
// Coefficients b_0..b_m of p_m(x) = sum b_k x^k (Higham 2005, (2.3) scaled to integers).
constexpr double kPade3[] = {120, 60, 12, 1};
constexpr double kPade5[] = {30240, 15120, 3360, 420, 30, 1};
constexpr double kPade7[] = {17297280, 8648640, 1995840, 277200, 25200, 1512, 56, 1};
constexpr double kPade9[] = {17643225600, 8821612800, 2075673600, 302702400, 30270240, 2162160, 110880, 3960, 90, 1};
constexpr double kPade13[] = {64764752532480000, 32382376266240000, 7771770303897600, 1187353796428800,
                              129060195264000,   10559470521600,    670442572800,     33522128640,
                              1323241920,        40840800,          960960,           16380,
                              182,               1};

// r_m(x) - 1 = (V - U)^-1 2U, with U and V the odd and even parts of p_m(x) (p_m(-x) = V - U): no 1 is
// subtracted, so small entries keep their relative accuracy.
Mat pade_expm1(const Mat& x, int m) {
  const double* b = m == 13 ? kPade13 : m == 3 ? kPade3 : m == 5 ? kPade5 : m == 7 ? kPade7 : kPade9;
  const Mat x2 = x * x;
  Mat odd, even;
  if (m == 13) {  // Higham's evaluation: 6 products for degree 13
    const Mat x4 = x2 * x2, x6 = x4 * x2;
    odd.noalias() = x6 * (b[13] * x6 + b[11] * x4 + b[9] * x2);
    odd += b[7] * x6 + b[5] * x4 + b[3] * x2;
    even.noalias() = x6 * (b[12] * x6 + b[10] * x4 + b[8] * x2);
    even += b[6] * x6 + b[4] * x4 + b[2] * x2;
  } else {
    Mat power = x2;
    odd = b[3] * x2;
    even = b[2] * x2;
    for (int k = 4; k <= m; k += 2) {
      power = (power * x2).eval();
      odd += b[k + 1] * power;
      even += b[k] * power;
    }
  }
  odd.diagonal().array() += b[1];  // the identity terms, on the diagonal only
  even.diagonal().array() += b[0];
  Mat u;
  u.noalias() = x * odd;
  even -= u;
  u *= 2.0;
  return Eigen::PartialPivLU<Mat>(even).solve(u);
}

// SO(2) in closed form: rot(theta) - I with cos - 1 = -2 sin^2(theta/2), and its log by atan2 (exp(-v) is
// exp(v)^T to the last bit, so exp(v) exp(-v) has log 0 exactly).
Mat rotation2_minus_identity(double theta) {
  const double h = std::sin(0.5 * theta), s = std::sin(theta);
  return (Eigen::Matrix2d() << -2.0 * h * h, -s, s, -2.0 * h * h).finished();
}

Mat log2(const Mat& r, double* max_angle) {
  if (r(0, 0) * r(1, 1) - r(0, 1) * r(1, 0) < 0.0)
    throw LogDomainError("log of a matrix with determinant -1 (not in SO(N))", kNaN);
  const double theta = std::atan2(0.5 * (r(1, 0) - r(0, 1)), 0.5 * (r(0, 0) + r(1, 1)));
  if (std::abs(theta) > std::numbers::pi - kLogDomainMargin)
    throw LogDomainError("log undefined: rotation angle " + std::to_string(std::abs(theta)) + " is at pi",
                         std::abs(theta));
  if (max_angle) *max_angle = std::abs(theta);
  return (Eigen::Matrix2d() << 0.0, -theta, theta, 0.0).finished();
}

}  // namespace

Mat expm1(const Mat& v) {
  const Eigen::Index n = v.rows();
  if (n == 2) return rotation2_minus_identity(0.5 * (v(1, 0) - v(0, 1)));
  // v is normal, so r_m's error is its error at v's eigenvalues i theta_k: the degree is chosen by a bound on
  // max |theta_k| = ||v||_2 <= min(||v||_1, ||v||_F / sqrt 2), then v is scaled by 2^-s into its range.
  const double bound = std::min(v.cwiseAbs().colwise().sum().maxCoeff(), v.norm() / std::numbers::sqrt2);
  if (!std::isfinite(bound)) return Mat::Constant(n, n, kNaN);
  int m = 13, s = 0;
  for (const auto& d : kPadeDegrees)
    if (bound <= d.theta) {
      m = d.m;
      break;
    }
  if (bound > kPadeDegrees[4].theta) s = static_cast<int>(std::ceil(std::log2(bound / kPadeDegrees[4].theta)));
  Mat e = pade_expm1(std::ldexp(1.0, -s) * v, m);
  for (int k = 0; k < s; ++k) e = (2.0 * e + e * e).eval();  // e^2x - 1 = 2 (e^x - 1) + (e^x - 1)^2
  // Squaring doubles the distance from the group each time: one Newton step towards the orthogonal polar
  // factor, X (3I - X^T X) / 2 with X = I + e, squares it away (d = I - X^T X, formed without the 1s). Without
  // squarings r_m(v) = p(v)^-T p(v) is orthogonal to the rounding of one LU solve.
  if (s == 0) return e;
  const Mat d = -(e + e.transpose() + e.transpose() * e);
  e += 0.5 * (d + e * d);
  return e;
}

Mat log(const Mat& r, double* max_angle) {
  check_orthogonal(r, 1e-8);
  if (r.rows() == 2) return log2(r, max_angle);
  if (auto l = log_from_symmetric_part(r, true, max_angle)) return *l;
  const SpectralForm s = spectral_form_of_rotation(r);
  if (max_angle) *max_angle = s.max_angle();
  return s.skew();
}

SpectralForm spectral_form_of_rotation(const Mat& r, double orthogonality_tol, double margin) {
  check_orthogonal(r, orthogonality_tol);
  SpectralForm s = schur_form_of_rotation(r, margin);
  if (auto l = log_from_symmetric_part(r, false, nullptr)) s.accurate_skew = std::move(*l);
  return s;
}

double max_angle(const Mat& r) {
  // Eigenvalues of an orthogonal matrix are e^{i theta}; their arguments are the rotation angles.
  const Eigen::VectorXcd ev = r.eigenvalues();
  double m = 0.0;
  for (Eigen::Index i = 0; i < ev.size(); ++i) m = std::max(m, std::abs(std::arg(ev(i))));
  return m;
}

Mat dexp(const SpectralForm& v, const Mat& u) { return AdFunction(v, dexp_function).apply(u); }
Mat dexpinv(const SpectralForm& v, const Mat& u) { return AdFunction(v, dexpinv_function).apply(u); }

namespace {
Mat matrix_of(const SpectralBasis& b) {
  Mat m;
  m.noalias() = b.times_basis * b.basis.transpose();
  return m;
}
}  // namespace

SpectralBasis dexp_in_spectral_basis(const SpectralForm& v) { return AdFunction(v, dexp_function).in_spectral_basis(); }
SpectralBasis dexpinv_in_spectral_basis(const SpectralForm& v) {
  return AdFunction(v, dexpinv_function).in_spectral_basis();
}
Mat dexp_matrix(const SpectralForm& v) { return matrix_of(dexp_in_spectral_basis(v)); }
Mat dexpinv_matrix(const SpectralForm& v) { return matrix_of(dexpinv_in_spectral_basis(v)); }

Mat ad_matrix(const Mat& v) {
  // [v, E_ab - E_ba] = v_:a e_b^T - v_:b e_a^T - e_a v_b: + e_b v_a:, assembled without N^3 products.
  const int n = static_cast<int>(v.rows());
  Mat out(algebra_dim(n), algebra_dim(n));
  Mat m = Mat::Zero(n, n);
  int col = 0;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b, ++col) {
      m.setZero();
      m.col(b) += v.col(a);
      m.col(a) -= v.col(b);
      m.row(a) -= v.row(b);
      m.row(b) += v.row(a);
      out.col(col) = vee(m);
    }
  return out;
}

Mat times_givens(const Mat& y, int a, int b, double t) {
  // y exp(t (E_ab - E_ba)): exp of a basis element is a plane rotation; only columns a and b change.
  Mat out = y;
  const double s = std::sin(t), cos_minus_1 = -2.0 * std::sin(0.5 * t) * std::sin(0.5 * t);
  out.col(a) += cos_minus_1 * y.col(a) - s * y.col(b);
  out.col(b) += s * y.col(a) + cos_minus_1 * y.col(b);
  return out;
}

Mat dexpinv_series(const Mat& v, const Mat& u, int p_max) {
  constexpr int kMaxOrder = 11;
  if (p_max < 0 || p_max > kMaxOrder) throw std::invalid_argument("dexpinv_series: p_max out of range");
  Mat ad = bracket(v, u);
  Mat result = u + 0.5 * ad;
  for (int p = 1; p <= p_max; ++p) {
    ad = bracket(v, ad);
    result += bernoulli_over_factorial(p) * ad;
    ad = bracket(v, ad);
  }
  return result;
}

}  // namespace lienewton::son
