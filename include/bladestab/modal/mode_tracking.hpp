#pragma once
// Following modes from one step of a sweep (a speed, a parameter value) to the next by the
// correlation of their shapes (mass-weighted MAC), so that a curve follows its mode through
// crossings and veering rather than taking the k-th lowest frequency.
#include <vector>

#include <Eigen/Dense>

namespace bladestab {

// Modes to solve at each step when `tracked` modes are followed: a few more (max(4, tracked/2)),
// so that modes entering from above can be followed; at most `dofs`.
int tracking_candidates(int tracked, int dofs);

// Greedy one-to-one assignment, largest correlation first: correlation(i, j) between tracked mode
// i and candidate j (e.g. a MAC in [0, 1]). result[i] is the candidate given to tracked mode i (−1
// when the candidates ran out), chosen[i] its correlation.
std::vector<int> assign_by_correlation(const Eigen::MatrixXd& correlation, std::vector<double>& chosen);

// MAC(a_i, b_j) = |a_iᴴ M b_j|² / ((a_iᴴ M a_i)(b_jᴴ M b_j)) for the columns of a and b.
Eigen::MatrixXd modal_assurance_matrix(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b, const Eigen::MatrixXd& M);

}  // namespace bladestab
