#pragma once
// Independent closed-form reference: natural frequencies of a clamped-free
// (cantilever) Timoshenko beam. Header-only, no dependency on the bladestab library.
//
// Model:  T = ½∫[ρA v̇² + ρI θ̇²] ds,   U = ½∫[EI θ'² + κGA (v' − θ)²] ds,   s ∈ [0, L],
//         v = θ = 0 at s = 0,   θ' = 0 and v' − θ = 0 at s = L.
// Frequency parameter  b = Λ = ω L² sqrt(ρA/(EI)),
// rotary inertia       r² = I/(A L²)            (= d̄², d̄ the slenderness),
// shear                s² = EI/(κGA L²)         (= d̄² E/(κG)).
//
// Frequency equation (Huang, T.C. 1961, "The effect of rotatory inertia and of shear
// deformation on the frequency and normal mode equations of uniform beams with simple
// end conditions", J. Appl. Mech. 28, 579–584), clamped-free case:
//
//   2 + [b²(r² − s²)² + 2] cosh(bα) cos(bβ) − [b(r² + s²)/sqrt(1 − b²r²s²)] sinh(bα) sin(bβ) = 0,
//
//   α, β = (1/√2) { ∓(r² + s²) + [ (r² − s²)² + 4/b² ]^½ }^½ .
//
// Since α²β² = (1 − b²r²s²)/b², i.e. sqrt(1 − b²r²s²) = bαβ, the singular coefficient is
// multiplied out:
//
//   f(b) = 2 + [b²(r² − s²)² + 2] C cos(bβ) − (r² + s²) (b/β) S sin(bβ),
//   C = cosh(bα),  S = sinh(bα)/(bα),
//
// an entire function of α². Above the cutoff b r s > 1 one has α² < 0; writing α = iα̂
// (α̂ = sqrt(−α²)) gives C = cos(bα̂), S = sin(bα̂)/(bα̂) — the "second spectrum" regime.
// f is finite and continuous through the cutoff (α = 0: C = S = 1), so every sign change of f
// is a true root, never a pole. Below the cutoff f is divided by C = cosh(bα) > 0 to keep it
// well scaled (this does not change its sign). Euler–Bernoulli limit r = s = 0:
// f = 2 + 2 cosh√b cos√b, i.e. 1 + cosh λ cos λ = 0 with Λ = λ².
#include <cmath>
#include <stdexcept>
#include <vector>

namespace reference {

namespace detail {

// Huang's clamped-free frequency function (scaled by 1/cosh(bα) below the cutoff), b > 0.
inline double timoshenko_cantilever_frequency_function(double b, double r2, double s2) {
    const double p = r2 + s2;
    const double q = (r2 - s2) * (r2 - s2);
    const double root = std::sqrt(q + 4.0 / (b * b));
    const double beta2 = 0.5 * (p + root);  // > 0
    // α² = ½(−p + root), computed without cancellation near the cutoff:
    const double alpha2 = (1.0 - b * b * r2 * s2) / (b * b * beta2);
    const double beta = std::sqrt(beta2);
    const double cb = std::cos(b * beta);
    const double sb = std::sin(b * beta);
    const double k = b * b * q + 2.0;

    const double a = std::sqrt(std::fabs(alpha2));
    const double x = b * a;  // bα (below cutoff) or bα̂ (above cutoff)
    if (alpha2 >= 0.0) {
        // Below the cutoff: divide by cosh(bα) > 0.
        const double tanh_over_x = x < 1e-8 ? 1.0 : std::tanh(x) / x;  // S / C
        return 2.0 / std::cosh(x) + k * cb - p * (b / beta) * tanh_over_x * sb;
    }
    // Above the cutoff (second spectrum): cosh → cos, sinh(x)/x → sin(x)/x.
    const double c = std::cos(x);
    const double sinc = x < 1e-8 ? 1.0 : std::sin(x) / x;
    return 2.0 + k * c * cb - p * (b / beta) * sinc * sb;
}

}  // namespace detail

// First `count` roots Λ of the clamped-free Timoshenko frequency equation (Huang 1961),
// in increasing order, for r² = d̄² (rotary inertia) and s² = d̄² E/(κG) (shear).
// Roots are bracketed by a geometric scan with relative step 1e-4 and refined by bisection
// to machine precision (relative width ≤ 1e-15).
inline std::vector<double> timoshenko_cantilever_lambdas(double slenderness, double youngs_over_kappa_shear,
                                                         int count) {
    if (!(slenderness >= 0.0) || !std::isfinite(slenderness))
        throw std::invalid_argument("timoshenko_cantilever_lambdas: slenderness must be finite and >= 0");
    if (!(youngs_over_kappa_shear >= 0.0) || !std::isfinite(youngs_over_kappa_shear))
        throw std::invalid_argument("timoshenko_cantilever_lambdas: E/(kappa G) must be finite and >= 0");
    if (count < 0) throw std::invalid_argument("timoshenko_cantilever_lambdas: count must be >= 0");

    const double r2 = slenderness * slenderness;
    const double s2 = r2 * youngs_over_kappa_shear;
    auto f = [r2, s2](double b) { return detail::timoshenko_cantilever_frequency_function(b, r2, s2); };

    std::vector<double> roots;
    roots.reserve(static_cast<std::size_t>(count));
    const double step = 1e-4;      // relative scan step
    const double b_max = 1e9;      // safety stop
    double lo = 1e-2;              // f(b) → 4 > 0 as b → 0; the first root of any cantilever is Λ > 1e-2
    double f_lo = f(lo);
    while (static_cast<int>(roots.size()) < count) {
        const double hi = lo * (1.0 + step);
        if (hi > b_max) throw std::runtime_error("timoshenko_cantilever_lambdas: root scan exceeded its range");
        const double f_hi = f(hi);
        if (f_hi == 0.0) {
            roots.push_back(hi);
        } else if ((f_lo < 0.0) != (f_hi < 0.0) && f_lo != 0.0) {
            double a = lo, fa = f_lo, c = hi;
            for (int it = 0; it < 200 && (c - a) > 1e-15 * c; ++it) {
                const double m = 0.5 * (a + c);
                const double fm = f(m);
                if (fm == 0.0) {
                    a = c = m;
                    break;
                }
                if ((fm < 0.0) == (fa < 0.0)) {
                    a = m;
                    fa = fm;
                } else {
                    c = m;
                }
            }
            roots.push_back(0.5 * (a + c));
        }
        lo = hi;
        f_lo = f_hi;
    }
    return roots;
}

}  // namespace reference
