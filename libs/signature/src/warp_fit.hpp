#pragma once
// The least-squares problem of motion.hpp and its fast evaluation.
//
// Problem. On components 1..K (K = m − 1) and N = max(16, 4m) column angles u_n = 2πn/N, with
// c_lk the components of line l of `to` and f_lk those of `from`,
//     cost(p) = Σ_n Σ_l r_ln²,   r_ln = 2·v_l(θ_n) − t_ln,   θ_n = u_n + a + b·cos u_n + c·sin u_n,
//     v_l(θ) = Re w_l,   w_l = Σ_k c_lk z^k,   z = e^{iθ},   t_ln = 2·Re Σ_k f_lk e^{ik·u_n},
// and, with d_l = ∂v_l/∂θ = −Im y_l, y_l = Σ_k k·c_lk z^k, the Jacobian row J_ln = 2·d_l·e_n,
// e_n = (1, cos u_n, sin u_n). Evaluated line by line this costs O(N·lines·m).
//
// Identity. Every sum over lines that the cost, JᵀJ and Jᵀr need is a trigonometric polynomial
// in θ whose coefficients do not depend on p:
//     Σ_l v_l² = ½ Σ_l (|w_l|² + Re w_l²) = Re Σ_{j=0}^{2K} α_j z^j,
//     Σ_l d_l² = ½ Σ_l (|y_l|² − Re y_l²) = Re Σ_{j=0}^{2K} β_j z^j,
//     Σ_l d_l v_l = ½ ∂/∂θ Σ_l v_l² = −½ Σ_j j·Im(α_j z^j),
//     Σ_l v_l t_ln = Re Σ_k A_nk z^k,   Σ_l d_l t_ln = −Im Σ_k k·A_nk z^k,   A_nk = Σ_l c_lk t_ln,
// where, with G_kk' = Σ_l c_lk conj(c_lk') and H_kk' = Σ_l c_lk c_lk' (so that
// Σ_l |w_l|² = Σ_kk' G_kk' z^{k−k'} and Σ_l w_l² = Σ_kk' H_kk' z^{k+k'}),
//     P_d = Σ_{k−k'=d} G_kk' (d = 0..K−1),   Q_s = Σ_{k+k'=s} H_kk' (s = 2..2K),
//     α_0 = ½ P_0,   α_j = P_j + ½ Q_j,   β_0 = ½ P'_0,   β_j = P'_j − ½ Q'_j   (j ≥ 1),
// P', Q' being the same sums of k·k'·G_kk' and k·k'·H_kk', and terms out of range 0 (G is
// Hermitian, so the z^{−d} terms of Σ|w|² are the conjugates of the z^d ones: hence P_j, not
// ½ P_j). Then
//     cost = Σ_n 4·(Σ_l v_l² − Σ_l v_l t_ln) + Σ_n Σ_l t_ln²,
//     JᵀJ  = Σ_n 4·Σ_l d_l² · e_n e_nᵀ,
//     Jᵀr  = Σ_n (4·Σ_l d_l v_l − 2·Σ_l d_l t_ln) · e_n,
// and Σ_n Σ_l t_ln² = 2N·Σ_l Σ_k |f_lk|² (Parseval: N > 2K, so no two frequencies alias). With
// c = a + ib, f = p + iq and xy_kk' = Σ_l x_lk y_lk' (LineSums, made once for every stage),
//     G_kk' = (aa + bb)_kk' + i(ba_kk' − ba_k'k),   H_kk' = (aa − bb)_kk' + i(ba_kk' + ba_k'k),
//     A_nk = 2 Σ_k' [(ap + i·bp)_kk' cos k'u_n − (aq + i·bq)_kk' sin k'u_n].
// An evaluation then costs O(N·m), whatever the number of lines; making the sums costs
// O(lines·m²) once, and A O(N·m²) per stage.
//
// Precision. The cost is a difference of sums as large as Σt² (the cost is residual²·Σt²), so
// its rounding error is of order 1e-16·Σt², not 1e-16·cost: measured ≤ 1e-14·Σt² against the
// line-by-line evaluation (motion_test.cpp), ≤ 1e-13 of the cost at residuals of 1% and more.
// Where LM compares costs closer than that (a converged fit solved again, as the stages do for
// m ≤ 4; views so alike that the residual is a few percent), it may take a different last
// step: (a, b, c) then moved by up to 2e-8 rad at m = 3, 2e-10 at m = 15 (300 random pairs).

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "omninav/signature/motion.hpp"
#include "omninav/signature/signature.hpp"

namespace omninav::signature::detail {

// The column angles a fit on m components samples: 4 per period of the highest component.
inline int warp_samples(int m) {
  return std::max(16, 4 * m);
}

struct WarpEvaluation {
  double cost = 0.0;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();    // JᵀJ
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // Jᵀr
};

// The least-squares problem above on components 1..m−1, as Levenberg-Marquardt sees it.
class WarpObjective {
 public:
  virtual ~WarpObjective() = default;
  virtual WarpEvaluation evaluate(const Eigen::Vector3d& p) const = 0;
  virtual std::size_t residual_count() const = 0;  // lines · N
  virtual double signal_rms() const = 0;           // √(Σ t² / residual_count)
};

// motion.hpp's three stages, each fitted on objective(m') for its m' ≤ m. estimate_motion()
// passes WarpFit; the tests pass the line-by-line evaluation to compare the two.
using ObjectiveFactory = std::function<std::unique_ptr<WarpObjective>(int m)>;
MotionEstimate fit_motion(const Signature& from, const Signature& to, int m,
                          const ObjectiveFactory& objective,
                          std::optional<double> known_turn = std::nullopt);

// The sums over lines of products of the components 1..m−1 of `to` (a + ib) and `from`
// (p + iq), once per pair of signatures: each stage's WarpFit takes its corner.
class LineSums {
 public:
  LineSums(const Signature& from, const Signature& to, int m);

  int lines() const { return lines_; }
  // xy_kk' = Σ_l x_lk y_lk' for k, k' = 1..m−1.
  double aa(int k, int k2) const { return to_to_(index(kRe, k), index(kRe, k2)); }
  double bb(int k, int k2) const { return to_to_(index(kIm, k), index(kIm, k2)); }
  double ba(int k, int k2) const { return to_to_(index(kIm, k), index(kRe, k2)); }
  // The same for x ∈ {a, b}, y ∈ {p, q}: K×K blocks, k, k' = 1..K, for K ≤ m − 1.
  auto ap(int K) const { return to_from_.block(index(kRe, 1), index(kRe, 1), K, K); }
  auto aq(int K) const { return to_from_.block(index(kRe, 1), index(kIm, 1), K, K); }
  auto bp(int K) const { return to_from_.block(index(kIm, 1), index(kRe, 1), K, K); }
  auto bq(int K) const { return to_from_.block(index(kIm, 1), index(kIm, 1), K, K); }
  // Σ_l Σ_{k=1}^{m'−1} |f_lk|², for m' ≤ m.
  double from_power(int m) const;

 private:
  enum Part { kRe = 0, kIm = 1 };
  // Where the real or imaginary part of component k is in the sums.
  int index(Part part, int k) const { return part * (m_ - 1) + k - 1; }
  int m_;
  int lines_;
  Eigen::MatrixXd to_to_;           // [a b]ᵀ[a b], lines summed over
  Eigen::MatrixXd to_from_;         // [a b]ᵀ[p q]
  std::vector<double> from_power_;  // Σ_l |f_lk|², k = 1..m−1
};

// The fast evaluation (the identity above) on components 1..m−1.
class WarpFit final : public WarpObjective {
 public:
  WarpFit(const LineSums& sums, int m);
  WarpEvaluation evaluate(const Eigen::Vector3d& p) const override;
  std::size_t residual_count() const override {
    return static_cast<std::size_t>(lines_) * static_cast<std::size_t>(samples_);
  }
  double signal_rms() const override { return signal_rms_; }

 private:
  int m_;
  int lines_;
  int samples_;
  std::vector<double> u_, cos_u_, sin_u_;
  std::vector<std::complex<double>> alpha_, beta_;  // j = 0..2(m−1)
  Eigen::MatrixXd a_re_, a_im_;                     // A_nk: N × (m−1), column k−1
  double target_energy_ = 0.0;                      // Σ_n Σ_l t_ln²
  double signal_rms_ = 0.0;
};

}  // namespace omninav::signature::detail
