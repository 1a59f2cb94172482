// Tables 4 and 5 of Sinha (2005): the first ten non-axial frequency parameters Λ of the paper
// blade at d̄ = 0.005, 0.01, 0.05, 0.1, at rest and at 300 rad/s, with the paper's sine basis.
//
// Finding: the tables match the sine basis with N = 20 terms per field (not the N = 10 the paper
// states) — to 0.02 % for most entries, 0.45 % at worst — except for three misprints. With N = 10 the higher modes
// are 1–6 % stiffer than the printed values; those entries are named below with our value.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>

#include "bladestab/damping.hpp"
#include "bladestab/modes.hpp"
#include "reference/timoshenko_cantilever.hpp"
#include "support/scenes.hpp"

using namespace bladestab;

namespace {

struct Column {
  double slenderness;
  std::vector<double> lambda;  // modes 1..10 as printed
};

const std::vector<Column> table4 = {  // Ω = 0
    {0.005, {3.5160, 22.0971, 61.5388, 120.3240, 198.2305, 293.0804, 408.1056, 539.8896, 688.3948, 853.3561}},
    {0.01, {3.4809, 21.9210, 60.8399, 117.9210, 192.1182, 281.9967, 384.3208, 500.4664, 627.4645, 764.5730}},
    {0.05, {3.4395, 19.1603, 46.8837, 79.6116, 114.9608, 151.3109, 187.5246, 220.7516, 238.7207, 250.6780}},
    {0.1, {3.2308, 14.5756, 31.8319, 48.4153, 62.6941, 68.4167, 81.0305, 89.5881, 102.6107, 110.3643}},
};
const std::vector<Column> table5 = {  // Ω = 300 rad/s
    {0.005, {15.3513, 43.7037, 88.2832, 150.8615, 225.0000, 327.9073, 443.4582, 576.4866, 725.7231, 891.3798}},
    {0.01, {8.3177, 28.9632, 68.6869, 127.7992, 200.3793, 290.1916, 393.9380, 510.3367, 637.6240, 775.0315}},
    {0.05, {3.7538, 19.5034, 47.2828, 80.0909, 115.5232, 151.9531, 188.2302, 221.3706, 238.9201, 251.1273}},
    {0.1, {3.3121, 14.6773, 31.9717, 48.5743, 62.8019, 68.5391, 81.1678, 89.7942, 102.7375, 110.6600}},
};

// Paper values that are wrong (SPEC §8 and misprints found here); excluded from both checks.
struct Misprint {
  int table;
  double slenderness;
  int mode;
  const char* why;
};
const std::vector<Misprint> misprints = {
    {4, 0.01, 1, "3.4809 is below the exact 3.51265, impossible for a Ritz upper bound (SPEC §8)"},
    {5, 0.005, 5, "225.0000: every other entry has four decimals of a computed value; N = 10 and 20 give 231.27, 230.58"},
    {5, 0.01, 4, "127.7992 is above even the N = 10 value 126.47; converged 126.004 (SPEC §7)"},
};

// N = 10 entries more than 1 % from the paper: our value, asserted to 1e-6.
struct Exception {
  int table;
  double slenderness;
  int mode;
  double paper, ours;
};
const std::vector<Exception> n10_exceptions = {
    {4, 0.005, 8, 539.8896, 547.060581},   //  +1.33 %
    {4, 0.005, 9, 688.3948, 697.350944},   //  +1.30 %
    {4, 0.005, 10, 853.3561, 903.762512},  //  +5.91 %
    {4, 0.01, 8, 500.4664, 507.843036},    //  +1.47 %
    {4, 0.01, 9, 627.4645, 636.550125},    //  +1.45 %
    {4, 0.01, 10, 764.5730, 810.166220},   //  +5.96 %
    {4, 0.05, 4, 79.6116, 80.410169},      //  +1.00 %
    {4, 0.05, 5, 114.9608, 116.244671},    //  +1.12 %
    {4, 0.05, 6, 151.3109, 153.521666},    //  +1.46 %
    {4, 0.05, 7, 187.5246, 190.025837},    //  +1.33 %
    {4, 0.05, 8, 220.7516, 223.409943},    //  +1.20 %
    {4, 0.05, 10, 250.6780, 253.362403},   //  +1.07 %
    {4, 0.1, 3, 31.8319, 32.160561},       //  +1.03 %
    {4, 0.1, 4, 48.4153, 48.957312},       //  +1.12 %
    {4, 0.1, 8, 89.5881, 90.716550},       //  +1.26 %
    {4, 0.1, 10, 110.3643, 111.880314},    //  +1.37 %
    {5, 0.005, 8, 576.4866, 584.377033},   //  +1.37 %
    {5, 0.005, 9, 725.7231, 735.439507},   //  +1.34 %
    {5, 0.005, 10, 891.3798, 930.796050},  //  +4.42 %
    {5, 0.01, 8, 510.3367, 517.923652},    //  +1.49 %
    {5, 0.01, 9, 637.6240, 646.904457},    //  +1.46 %
    {5, 0.01, 10, 775.0315, 817.241625},   //  +5.45 %
    {5, 0.05, 4, 80.0909, 80.894476},      //  +1.00 %
    {5, 0.05, 5, 115.5232, 116.809850},    //  +1.11 %
    {5, 0.05, 6, 151.9531, 154.163511},    //  +1.45 %
    {5, 0.05, 7, 188.2302, 190.726590},    //  +1.33 %
    {5, 0.05, 8, 221.3706, 223.960092},    //  +1.17 %
    {5, 0.05, 10, 251.1273, 253.816282},   //  +1.07 %
    {5, 0.1, 3, 31.9717, 32.300010},       //  +1.03 %
    {5, 0.1, 4, 48.5743, 49.114312},       //  +1.11 %
    {5, 0.1, 8, 89.7942, 90.915464},       //  +1.25 %
    {5, 0.1, 10, 110.6600, 112.176921},    //  +1.37 %
};

std::vector<double> non_axial_lambdas(double slenderness, double speed, int terms) {
  const Scene s = testing_support::paper_scene({"model.basis=sine", "model.terms=" + std::to_string(terms),
                                                "blade.slenderness=" + std::to_string(slenderness),
                                                "operation.speed_rad_s=" + std::to_string(speed)});
  const BladeModel m = assemble_model(s);
  const ModalSolution sol = solve_modes(m, system_at(m, speed, damping_matrix(m, s.damping, speed)), speed, 0,
                                        EigenSolverKind::dense);
  std::vector<double> out;
  for (const Mode& mode : sol.modes) {
    if (mode.family != ModeFamily::axial && out.size() < 10) out.push_back(mode.lambda);
  }
  return out;
}

template <class List>
const typename List::value_type* find_entry(const List& list, int table, double d, int mode) {
  for (const auto& e : list) {
    if (e.table == table && e.slenderness == d && e.mode == mode) return &e;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("paper Tables 4 and 5 with the paper's basis, N = 10: within 1 % but for named entries", "[modes][paper]") {
  int within = 0, named = 0;
  for (int table : {4, 5}) {
    for (const Column& column : table == 4 ? table4 : table5) {
      const std::vector<double> ours = non_axial_lambdas(column.slenderness, table == 4 ? 0 : 300, 10);
      REQUIRE(ours.size() == 10);
      for (int k = 0; k < 10; ++k) {
        INFO("Table " << table << ", d = " << column.slenderness << ", mode " << k + 1 << ": paper "
                      << column.lambda[k] << ", ours " << ours[k]);
        const double deviation = std::abs(ours[k] / column.lambda[k] - 1);
        if (find_entry(misprints, table, column.slenderness, k + 1) != nullptr) {
          ++named;
        } else if (const Exception* e = find_entry(n10_exceptions, table, column.slenderness, k + 1)) {
          CHECK(ours[k] == Approx(e->ours).epsilon(1e-6));
          CHECK(deviation > 0.0099);
          ++named;
        } else {
          CHECK(deviation <= 0.01);
          ++within;
        }
      }
    }
  }
  CHECK(within == 80 - 3 - 32);
  CHECK(named == 35);
  // The SPEC §8 misprint really is below the exact value.
  CHECK(3.4809 < reference::timoshenko_cantilever_lambdas(0.01, 2 * 1.3 / 0.833, 1)[0]);
}

TEST_CASE("paper Tables 4 and 5 are the sine basis with N = 20", "[modes][paper]") {
  for (int table : {4, 5}) {
    for (const Column& column : table == 4 ? table4 : table5) {
      const std::vector<double> ours = non_axial_lambdas(column.slenderness, table == 4 ? 0 : 300, 20);
      for (int k = 0; k < 10; ++k) {
        if (find_entry(misprints, table, column.slenderness, k + 1) != nullptr) continue;
        INFO("Table " << table << ", d = " << column.slenderness << ", mode " << k + 1 << ": paper "
                      << column.lambda[k] << ", ours " << ours[k]);
        // Stubby columns agree to 0.1 % (modes 3–10 to 0.02 %); the slender ones' modes 2–6 differ
        // by up to 0.44 %.
        CHECK(std::abs(ours[k] / column.lambda[k] - 1) <= (column.slenderness >= 0.05 ? 1e-3 : 4.5e-3));
      }
    }
  }
}
