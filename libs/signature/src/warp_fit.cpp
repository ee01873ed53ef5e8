#include "warp_fit.hpp"

#include <algorithm>
#include <cmath>

#include "fast_math.hpp"
#include "omninav/core/angles.hpp"
#include "simd_dispatch.hpp"

namespace omninav::signature::detail {
namespace {

using Complex = std::complex<double>;

// Samples evaluated together: enough independent chains of powers z^j to hide their latency,
// few enough that the block's sums stay in registers and L1.
constexpr int kBlock = 16;

// Per sample of a block, the sums over lines of warp_fit.hpp's identity.
struct SampleSums {
  double vv[kBlock];  // Σ_l v_l²
  double dd[kBlock];  // Σ_l d_l²
  double dv[kBlock];  // Σ_l d_l v_l
  double vt[kBlock];  // Σ_l v_l t_ln
  double dt[kBlock];  // Σ_l d_l t_ln
};

// `count` ≤ kBlock samples at e^{iθ} = (cos_theta, sin_theta); A_nk of sample i and component k
// at a_re[(k − 1)·a_stride + i]. The loops run over the samples, so each sample's sums are made
// in the same order whether they vectorise or not, and both clones give the same doubles.
OMNINAV_KERNEL_CLONES
void sample_sums(int count, int m, const double* __restrict cos_theta,
                 const double* __restrict sin_theta, const Complex* __restrict alpha,
                 const Complex* __restrict beta, const double* __restrict a_re,
                 const double* __restrict a_im, std::ptrdiff_t a_stride, SampleSums& sums) {
  double zr[kBlock], zi[kBlock];  // z^j
  double vv[kBlock], dd[kBlock], dv[kBlock], vt[kBlock], dt[kBlock];
  for (int i = 0; i < count; ++i) {
    zr[i] = cos_theta[i];
    zi[i] = sin_theta[i];
    vv[i] = alpha[0].real();
    dd[i] = beta[0].real();
    dv[i] = vt[i] = dt[i] = 0.0;
  }
  // j = 1..m−1: the signal's own components, with the target's A_nj.
  for (int j = 1; j < m; ++j) {
    const double ar = alpha[j].real(), ai = alpha[j].imag();
    const double br = beta[j].real(), bi = beta[j].imag();
    const double jar = j * ar, jai = j * ai, weight = j;
    const double* __restrict tr = a_re + (j - 1) * a_stride;
    const double* __restrict ti = a_im + (j - 1) * a_stride;
    for (int i = 0; i < count; ++i) {
      vv[i] += ar * zr[i] - ai * zi[i];
      dv[i] += jar * zi[i] + jai * zr[i];
      dd[i] += br * zr[i] - bi * zi[i];
      vt[i] += tr[i] * zr[i] - ti[i] * zi[i];
      dt[i] += weight * (tr[i] * zi[i] + ti[i] * zr[i]);
      const double next_r = zr[i] * cos_theta[i] - zi[i] * sin_theta[i];
      zi[i] = zr[i] * sin_theta[i] + zi[i] * cos_theta[i];
      zr[i] = next_r;
    }
  }
  // j = m..2(m−1): products of two components only.
  for (int j = m; j <= 2 * (m - 1); ++j) {
    const double ar = alpha[j].real(), ai = alpha[j].imag();
    const double br = beta[j].real(), bi = beta[j].imag();
    const double jar = j * ar, jai = j * ai;
    for (int i = 0; i < count; ++i) {
      vv[i] += ar * zr[i] - ai * zi[i];
      dv[i] += jar * zi[i] + jai * zr[i];
      dd[i] += br * zr[i] - bi * zi[i];
      const double next_r = zr[i] * cos_theta[i] - zi[i] * sin_theta[i];
      zi[i] = zr[i] * sin_theta[i] + zi[i] * cos_theta[i];
      zr[i] = next_r;
    }
  }
  for (int i = 0; i < count; ++i) {
    sums.vv[i] = vv[i];
    sums.dd[i] = dd[i];
    sums.dv[i] = -0.5 * dv[i];  // −½ Σ_j j·Im(α_j z^j)
    sums.vt[i] = vt[i];
    sums.dt[i] = -dt[i];  // −Im Σ_k k·A_nk z^k
  }
}

}  // namespace

LineSums::LineSums(const Signature& from, const Signature& to, int m)
    : m_(m), lines_(from.lines()), from_power_(static_cast<std::size_t>(m), 0.0) {
  const int K = m - 1;
  // Components 1..m−1 of every line, a + ib = |F|·(cos, sin) arg F, for each signature.
  const std::size_t count = static_cast<std::size_t>(lines_) * K;
  std::vector<double> phases(count), sines(count), cosines(count);
  const auto parts = [&](const Signature& signature, Eigen::MatrixXd& out) {
    out.resize(lines_, 2 * K);
    for (int line = 0; line < lines_; ++line) {
      for (int k = 1; k < m; ++k) {
        phases[static_cast<std::size_t>(line) * K + k - 1] =
            signature.phase_rad[signature.at(line, k)];
      }
    }
    sin_cos(phases.data(), count, sines.data(), cosines.data());
    for (int line = 0; line < lines_; ++line) {
      for (int k = 1; k < m; ++k) {
        const std::size_t i = static_cast<std::size_t>(line) * K + k - 1;
        const double magnitude = signature.magnitude[signature.at(line, k)];
        out(line, index(kRe, k)) = magnitude * cosines[i];
        out(line, index(kIm, k)) = magnitude * sines[i];
      }
    }
  };
  Eigen::MatrixXd to_parts, from_parts;
  parts(to, to_parts);
  parts(from, from_parts);
  to_to_.noalias() = to_parts.transpose() * to_parts;
  to_from_.noalias() = to_parts.transpose() * from_parts;
  for (int k = 1; k < m; ++k) {
    from_power_[static_cast<std::size_t>(k)] =
        from_parts.col(index(kRe, k)).squaredNorm() + from_parts.col(index(kIm, k)).squaredNorm();
  }
}

double LineSums::from_power(int m) const {
  double power = 0.0;
  for (int k = 1; k < m; ++k) power += from_power_[static_cast<std::size_t>(k)];
  return power;
}

WarpFit::WarpFit(const LineSums& sums, int m)
    : m_(m), lines_(sums.lines()), samples_(warp_samples(m)) {
  const int K = m - 1;
  u_.resize(static_cast<std::size_t>(samples_));
  cos_u_.resize(u_.size());
  sin_u_.resize(u_.size());
  for (int n = 0; n < samples_; ++n) {
    u_[n] = kTwoPi * n / samples_;
    cos_u_[n] = std::cos(u_[n]);
    sin_u_[n] = std::sin(u_[n]);
  }

  // α_j and β_j from the G and H of the identity.
  alpha_.assign(static_cast<std::size_t>(2 * K + 1), Complex(0.0, 0.0));
  beta_.assign(alpha_.size(), Complex(0.0, 0.0));
  for (int k = 1; k <= K; ++k) {
    for (int k2 = 1; k2 <= K; ++k2) {
      const double aa = sums.aa(k, k2), bb = sums.bb(k, k2);
      const double ba = sums.ba(k, k2), ab = sums.ba(k2, k);
      const Complex g(aa + bb, ba - ab), h(aa - bb, ba + ab);
      const double weight = static_cast<double>(k) * k2;
      alpha_[k + k2] += 0.5 * h;
      beta_[k + k2] -= 0.5 * weight * h;
      if (k == k2) {
        alpha_[0] += 0.5 * g;
        beta_[0] += 0.5 * weight * g;
      } else if (k > k2) {
        alpha_[k - k2] += g;
        beta_[k - k2] += weight * g;
      }
    }
  }

  // A_nk; cos k'u_n = cos u_j with j = k'n mod N, as the samples are uniform.
  Eigen::MatrixXd cos_ku(samples_, K), sin_ku(samples_, K);
  for (int n = 0; n < samples_; ++n) {
    for (int k = 1; k <= K; ++k) {
      const int j = (k * n) % samples_;
      cos_ku(n, k - 1) = cos_u_[j];
      sin_ku(n, k - 1) = sin_u_[j];
    }
  }
  a_re_.noalias() = cos_ku * sums.ap(K).transpose();
  a_re_.noalias() -= sin_ku * sums.aq(K).transpose();
  a_re_ *= 2.0;
  a_im_.noalias() = cos_ku * sums.bp(K).transpose();
  a_im_.noalias() -= sin_ku * sums.bq(K).transpose();
  a_im_ *= 2.0;

  target_energy_ = 2.0 * samples_ * sums.from_power(m);
  signal_rms_ = std::sqrt(target_energy_ / static_cast<double>(residual_count()));
}

WarpEvaluation WarpFit::evaluate(const Eigen::Vector3d& p) const {
  double residual = 0.0;                                     // Σ_n 4·(Σ v² − Σ v t)
  double n0 = 0, nc = 0, ns = 0, ncc = 0, ncs = 0, nss = 0;  // Σ_n 4·Σ d² · (1, c, s, c², cs, s²)
  double g0 = 0, gc = 0, gs = 0;  // Σ_n (4·Σ d v − 2·Σ d t) · (1, c, s)
  double theta[kBlock], cos_theta[kBlock], sin_theta[kBlock];
  SampleSums sums;
  for (int first = 0; first < samples_; first += kBlock) {
    const int count = std::min(kBlock, samples_ - first);
    for (int i = 0; i < count; ++i) {
      const int n = first + i;
      theta[i] = u_[n] + p[0] + p[1] * cos_u_[n] + p[2] * sin_u_[n];
    }
    sin_cos(theta, static_cast<std::size_t>(count), sin_theta, cos_theta);
    sample_sums(count, m_, cos_theta, sin_theta, alpha_.data(), beta_.data(), a_re_.data() + first,
                a_im_.data() + first, a_re_.outerStride(), sums);
    for (int i = 0; i < count; ++i) {
      const double c = cos_u_[first + i], s = sin_u_[first + i];
      residual += 4.0 * (sums.vv[i] - sums.vt[i]);
      const double w = 4.0 * sums.dd[i];
      n0 += w;
      nc += w * c;
      ns += w * s;
      ncc += w * c * c;
      ncs += w * c * s;
      nss += w * s * s;
      const double g = 4.0 * sums.dv[i] - 2.0 * sums.dt[i];
      g0 += g;
      gc += g * c;
      gs += g * s;
    }
  }
  WarpEvaluation e;
  // A perfect fit can come out a rounding error below zero.
  e.cost = std::max(0.0, residual + target_energy_);
  e.normal << n0, nc, ns, nc, ncc, ncs, ns, ncs, nss;
  e.gradient << g0, gc, gs;
  return e;
}

}  // namespace omninav::signature::detail
