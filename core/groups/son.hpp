#pragma once
// SO(N), any N >= 2, through the spectral (real Schur) structure of normal matrices.
// Coordinates on so(N) use the paper's basis b = E_ij - E_ji, i < j, in row-major order (1,2), (1,3), ...,
// (1,N), (2,3), ..., (N-1,N); q = N(N-1)/2. The 2-norm of the coordinates is ||.||_F / sqrt(2).
//
// A skew matrix v and a rotation R = exp(v) share an orthogonal Q with Q^T v Q = blockdiag(theta_k J, 0) and
// Q^T R Q = blockdiag(rot(theta_k), 1), J = [0 -1; 1 0]. That one SpectralForm yields exp, log, and the
// exact dexp / dexpinv in O(N^3): on the eigenvectors of v, ad_v acts by lambda_i - lambda_j, so any analytic
// F(ad_v) is applied blockwise in Q's basis (see apply_ad_function in son.cpp).
#include <Eigen/Dense>
#include <stdexcept>

#include <vector>

#include "log_domain.hpp"

namespace lienewton::son {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

inline int algebra_dim(int n) { return n * (n - 1) / 2; }

using lienewton::kLogDomainMargin;
using lienewton::LogDomainError;

Mat hat(const Vec& alpha, int n);
Vec vee(const Mat& m);  // coordinates of the skew part (m - m^T)/2

struct SpectralForm {
  Mat q;                     // orthogonal
  struct Block {
    int start;               // first row/column in Q's basis
    int size;                // 1 (eigenvalue 0 of v / 1 of R) or 2 (rotation by theta)
    double theta;            // 0 for size 1
  };
  std::vector<Block> blocks;
  Mat accurate_skew;         // log computed from the symmetric part (see log below), when it was; else empty
  double max_angle() const;  // largest |theta|
  Mat skew() const;          // v: accurate_skew if set, else Q blockdiag(theta J, 0) Q^T; exactly skew
  Mat rotation() const;      // exp(v) = Q blockdiag(rot theta, 1) Q^T
};

SpectralForm spectral_form_of_skew(const Mat& v);
// Throws LogDomainError. orthogonality_tol bounds ||R^T R - I||_F.
SpectralForm spectral_form_of_rotation(const Mat& r, double orthogonality_tol = 1e-8,
                                       double margin = kLogDomainMargin);

// exp(v) - I by Pade scaling and squaring (degree 3..13 chosen by a bound on v's largest angle, Higham 2005),
// squared as e^2x - 1 = 2 (e^x - 1) + (e^x - 1)^2 and ended by one Newton step towards the orthogonal polar
// factor: orthogonal to rounding (~N eps) at any angle. Small entries keep their relative accuracy, so
// y exp(v) = y + y expm1(v) stays on the group.
Mat expm1(const Mat& v);
inline Mat exp(const Mat& v) { return Mat::Identity(v.rows(), v.cols()) + expm1(v); }

// log R = F(S) A with S = (R + R^T)/2, A = (R - R^T)/2 and F(cos t) = t / sin t, smooth on [-1 + delta, 1]:
// S and A commute, and on each rotation plane S = cos t, A = sin t J. Taken through S's eigen-decomposition
// when every angle is below 3pi/4 (F stays well-conditioned): small angles then keep their relative accuracy,
// which a Schur form of R (absolute accuracy eps) loses. Otherwise the Schur form. Throws LogDomainError.
Mat log(const Mat& r, double* max_angle = nullptr);
double max_angle(const Mat& r);  // largest rotation angle of an orthogonal r (no domain check)

inline Mat bracket(const Mat& a, const Mat& b) { return a * b - b * a; }

// Exact differentials, applied to a skew U in O(N^3):
//   dexp_v(U)    = sum (-1)^k / (k+1)! ad_v^k (U)                    (2.10)
//   dexpinv_v(U) = U + 1/2 [v,U] + sum_p B_2p/(2p)! ad_v^2p (U)       (3.9)
Mat dexp(const SpectralForm& v, const Mat& u);
Mat dexpinv(const SpectralForm& v, const Mat& u);
// The spectral basis P of v: the q x q orthogonal matrix of U -> Q U Q^T on the paper's coordinates (column
// (ij) = vee(Q (E_ij - E_ji) Q^T)), with F(ad_v) P for F = dexp or dexpinv, both in O(N^4). In Q's basis F(ad_v)
// is block-sparse (see AdFunction in son.cpp), so its matrix is F(ad_v) = (F(ad_v) P) P^T, and a Newton system
// D u = -f with D = F(ad_v) - H is solved as (F(ad_v) P - H P) w = -f, u = P w, without ever forming F(ad_v).
struct SpectralBasis {
  Mat basis;        // P
  Mat times_basis;  // F(ad_v) P
};
SpectralBasis dexp_in_spectral_basis(const SpectralForm& v);
SpectralBasis dexpinv_in_spectral_basis(const SpectralForm& v);
// Their q x q matrices on the paper's basis, (F(ad_v) P) P^T: O(N^4) plus one q x q product.
Mat dexp_matrix(const SpectralForm& v);
Mat dexpinv_matrix(const SpectralForm& v);
// The q x q matrix of ad_v = [v, .], in O(N^4).
Mat ad_matrix(const Mat& v);
// y exp(t b) for the basis element b = E_ab - E_ba (a < b): a plane rotation of columns a and b, O(N).
Mat times_givens(const Mat& y, int a, int b, double t);
// (3.9) truncated after ad_v^(2 p_max): for comparison with the exact form.
Mat dexpinv_series(const Mat& v, const Mat& u, int p_max);

}  // namespace lienewton::son
