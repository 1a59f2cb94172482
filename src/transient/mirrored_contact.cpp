// The contact of an even pulse from its first half (exact_stepping.hpp, docs/theory.md §5.8).
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include "bladestab/ltp/reversing_symmetry.hpp"
#include "bladestab/transient/exact_stepping.hpp"

namespace bladestab {
namespace {

// Offsets equal up to rounding on the scale of the contact.
bool same_offset(double a, double b, double contact) { return std::abs(a - b) <= 1e-12 * contact; }

// The propagators of the first half's segments [grid_k, grid_{k+1}], and products of them.
struct HalfContact {
  std::vector<double> grid;
  std::vector<Eigen::MatrixXd> maps;
  std::vector<double> errors;
  double contact = 0;

  std::size_t at(double offset) const {
    const auto it = std::find_if(grid.begin(), grid.end(), [&](double g) { return same_offset(g, offset, contact); });
    if (it == grid.end()) throw std::logic_error("mirrored contact: an offset off the first half's grid");
    return static_cast<std::size_t>(it - grid.begin());
  }
  // P(b, a) for grid points a ≤ b, and the sum of its segments' error bounds.
  Eigen::MatrixXd between(double a, double b, double& error) const {
    Eigen::MatrixXd P = Eigen::MatrixXd::Identity(maps.front().rows(), maps.front().cols());
    for (std::size_t k = at(a); k < at(b); ++k) {
      P = maps[k] * P;
      error += errors[k];
    }
    return P;
  }
};

// The augmented map [[P, c₊, c₋], [0, I]] as the stepper keeps it, [[P, c₊ + c₋], [0, 1]].
Eigen::MatrixXd joined_forcing(const Eigen::MatrixXd& M) {
  const Eigen::Index s = M.rows() - 2;
  Eigen::MatrixXd map = Eigen::MatrixXd::Zero(s + 1, s + 1);
  map.topLeftCorner(s, s) = M.topLeftCorner(s, s);
  map.col(s).head(s) = M.col(s).head(s) + M.col(s + 1).head(s);
  map(s, s) = 1;
  return map;
}

}  // namespace

std::optional<ExactStepper::Mirror> ExactStepper::contact_mirror(const Eigen::MatrixXd& A_free, const Eigen::MatrixXd& B,
                                                                 const PulseTrain& pulses, bool damped) {
  const Eigen::Index s = A_free.rows() - 1;
  if (damped || !pulses.even_profile()) return std::nullopt;
  const std::optional<Eigen::VectorXd> r = reversing_signature(A_free.topLeftCorner(s, s), B.topLeftCorner(s, s));
  if (!r) return std::nullopt;
  // R B R = −B asks r_i b_i r_c = −b_i of a forcing column with the constant's sign r_c: the
  // forcing on coordinates with r_i = −1 goes with a constant of sign +1, the rest with −1.
  Mirror m{Eigen::MatrixXd::Zero(s + 2, s + 2), Eigen::MatrixXd::Zero(s + 2, s + 2), Eigen::VectorXd(s + 2)};
  m.A.topLeftCorner(s, s) = A_free.topLeftCorner(s, s);
  m.B.topLeftCorner(s, s) = B.topLeftCorner(s, s);
  for (Eigen::Index i = 0; i < s; ++i) m.B(i, (*r)(i) < 0 ? s : s + 1) = B(i, s);
  m.signature << *r, 1, -1;
  return m;
}

std::vector<ExactStepper::Integrated> ExactStepper::mirrored_pieces(const std::vector<std::pair<double, double>>& pieces,
                                                                    int threads,
                                                                    const std::function<void(int, int)>& progress) const {
  HalfContact half;
  half.contact = pulses_.contact_time_s;
  const double c = half.contact / 2;
  // The first half's points: a piece's ends there, or their mirror images 2c − t, and c where a
  // piece spans it.
  for (const auto& [a, b] : pieces) {
    for (const double t : {a, b}) half.grid.push_back(std::min(t, 2 * c - t));
    if (a < c && b > c) half.grid.push_back(c);
  }
  std::sort(half.grid.begin(), half.grid.end());
  half.grid.erase(std::unique(half.grid.begin(), half.grid.end(),
                              [&](double x, double y) { return same_offset(x, y, half.contact); }),
                  half.grid.end());
  // At least two segments, on any number of threads (the propagators, and so the run, must not
  // depend on it): the longest is halved until there are, so that two threads share the half as
  // they shared the two halves.
  while (half.grid.size() < 3) {
    std::size_t longest = 0;
    for (std::size_t k = 1; k + 1 < half.grid.size(); ++k) {
      if (half.grid[k + 1] - half.grid[k] > half.grid[longest + 1] - half.grid[longest]) longest = k;
    }
    half.grid.insert(half.grid.begin() + static_cast<std::ptrdiff_t>(longest) + 1,
                     0.5 * (half.grid[longest] + half.grid[longest + 1]));
  }
  std::vector<std::pair<double, double>> segments;
  for (std::size_t k = 0; k + 1 < half.grid.size(); ++k) segments.emplace_back(half.grid[k], half.grid[k + 1]);
  std::vector<Integrated> integrated = integrate_side_by_side(mirror_->A, mirror_->B, 2, segments, threads, progress);
  long steps = 0;
  for (Integrated& segment : integrated) {
    half.maps.push_back(std::move(segment.piece.map));
    half.errors.push_back(segment.error);
    steps += segment.steps;
  }
  // A piece within the first half is a product of segments; past c it is R P(2c − a, 2c − b)⁻¹ R
  // of its mirror image (reversing_symmetry.hpp), and one across c both, joined at c.
  const auto R = mirror_->signature.asDiagonal();
  std::vector<Integrated> out;
  for (const auto& [a, b] : pieces) {
    Integrated piece;
    Eigen::MatrixXd P = Eigen::MatrixXd::Identity(mirror_->A.rows(), mirror_->A.cols());
    if (a < c && !same_offset(a, c, half.contact)) P = half.between(a, std::min(b, c), piece.error);
    if (b > c && !same_offset(b, c, half.contact)) {
      const double from = std::max(a, c);
      const Eigen::MatrixXd mirrored = half.between(2 * c - b, 2 * c - from, piece.error);
      P = R * mirrored.partialPivLu().inverse() * R * P;
    }
    piece.piece = {a, b, joined_forcing(P), {}};
    out.push_back(std::move(piece));
  }
  if (!out.empty()) out.front().steps = steps;
  return out;
}

}  // namespace bladestab
