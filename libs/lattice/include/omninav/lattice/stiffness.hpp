#pragma once
// The spring coefficient of Menegatti et al. 2004, Eq. 5, K(x) = exp(E(x)·log 0.1 / E(x₁)):
// a spring whose estimated length x is near the correlation range x₁ is unreliable and pulls
// with at most a tenth of a short spring's force (§3.2, Fig. 12).
//
// Our reading of the unclear parts: E(x) is the error of a distance estimated from similarity
// (Fig. 12a: small at short range, growing quickly). We model it as growing with the square of
// the distance, E(x) = x², the simplest curve with Fig. 12a's shape; then
//   K(x) = 0.1^((x / x₁)²),  K(0) = 1, K(x₁) = 0.1, K(2·x₁) = 10⁻⁴.

namespace omninav::lattice {

double spring_stiffness(double estimated_length_m, double correlation_range_m);

// The estimated length beyond which K falls below `min_stiffness`: springs longer than this are
// negligible and can be dropped to keep large memories sparse.
double negligible_length_m(double correlation_range_m, double min_stiffness);

}  // namespace omninav::lattice
