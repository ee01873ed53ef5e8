#pragma once
// Comparing signatures (Menegatti et al. 2004, §2.2).
//
// Eq. 2, the dissimilarity, the L1 distance between the magnitudes:
//     Dis(O_i, O_j) = Σ_{y<l} Σ_{k<m} |F_iy(k) − F_jy(k)|
// (the text writes F, the Fourier coefficients, but says the magnitudes carry the place and
// the rotation invariance of §2.1 needs them: we read |F| throughout). Eq. 6 (§4) weights each
// component: Σ_y Σ_k α_k |F_iy(k) − F_jy(k)|; with every α_k = 1 it is Eq. 2.
//
// Eq. 3, the similarity, Dis rescaled to 0..1000 over a reference set:
//     Sim = 1000 − 1000 (Dis − Min Dis) / (Max Dis − Min Dis)
// Our reading of "the rescaling is done on the whole dataset of reference images": for a query
// (the current image), Min and Max run over its dissimilarities to every reference image, so
// its best match scores 1000 and its worst 0 (rescale_similarities); for pairs of reference
// images (the lattice), over all pairs (similarity_0_1000 with that range).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "omninav/signature/signature.hpp"

namespace omninav {
class ConfigReader;
}

namespace omninav::signature {

// The α_k of Eq. 6 for k = 0..m−1. Fewer values than components: the last one repeats, so
// {1} is Eq. 2. Weights must be ≥ 0 (they scale magnitudes, see SignatureIndex).
struct ComponentWeights {
  std::vector<double> alpha{1.0};

  double operator[](int k) const;
};

// Parses "1, 1, 0.5" (comma-separated, each 0..1e6). Throws ConfigError naming `where`.
ComponentWeights parse_component_weights(const std::string& text, const std::string& where);
std::string to_string(const ComponentWeights& weights);

// Eq. 2 / Eq. 6 over the first `components` components of both (−1: all of them). Throws
// UsageError when the two differ in lines or have fewer components than asked for.
double dissimilarity(const Signature& a, const Signature& b, int components = -1,
                     const ComponentWeights& weights = {});

// Beyond the papers: the dissimilarity of the coefficients themselves, magnitudes and phases,
// once `from` is turned by `turn_rad` (phase_heading.hpp's sign: heading(to) − heading(from)):
//     Σ_y Σ_{k<m} α_k |F_to,y(k) − e^{−ik·turn} F_from,y(k)|.
// Eq. 2 compares magnitudes only, which forgets where along the horizon each row's structure
// lies, so places whose rows hold the same mix of features in another arrangement look alike;
// the phases, aligned by the turn, keep the arrangement. By Parseval it is the image-space
// distance of the low-pass panoramas at that rotation (the visual compass's, Labrosse 2006, §2), in
// L1 over the coefficients. ≥ Eq. 6's value for the same weights (|a − b| ≥ ||a| − |b||). Throws as
// dissimilarity().
double rotational_dissimilarity(const Signature& from, const Signature& to, double turn_rad,
                                int components = -1, const ComponentWeights& weights = {});

// Eq. 3 for one value, given the range of the reference set; clamped to [0, 1000]. A
// degenerate range (max ≤ min) gives 1000.
double similarity_0_1000(double dissimilarity, double min_dissimilarity, double max_dissimilarity);

// Eq. 3 over a query's dissimilarities to a reference set (min and max taken over them).
std::vector<double> rescale_similarities(std::span<const double> dissimilarities);

}  // namespace omninav::signature
