// The order of visits: Held-Karp against every permutation, and the heuristic (nearest
// neighbour + 2-opt + Or-opt) within 10 % of Held-Karp's optimum on random small instances,
// closed and open.
#include "hylo/inspection/tour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace hylo::inspection {
namespace {

// Euclidean costs of random points (the start first), or, with `clustered`, points in a few
// tight groups far apart (where nearest neighbour alone goes wrong).
CostMatrix RandomInstance(int n, unsigned seed, bool clustered) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 100.0), near(-3.0, 3.0);
  std::vector<Eigen::Vector2d> p;
  std::vector<Eigen::Vector2d> centres;
  for (int k = 0; k < 3; ++k) centres.emplace_back(u(rng), u(rng));
  for (int i = 0; i < n; ++i) {
    p.push_back(clustered ? centres[i % 3] + Eigen::Vector2d(near(rng), near(rng))
                          : Eigen::Vector2d(u(rng), u(rng)));
  }
  CostMatrix c(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) c(i, j) = (p[i] - p[j]).norm();
  return c;
}

bool IsTourFromZero(const std::vector<int>& order, int n) {
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  return !order.empty() && order.front() == 0 && sorted == all;
}

double BruteForceOptimum(const CostMatrix& c, bool closed) {
  std::vector<int> order(c.rows());
  std::iota(order.begin(), order.end(), 0);
  double best = 1e300;
  do {
    best = std::min(best, TourCost(c, order, closed));
  } while (std::next_permutation(order.begin() + 1, order.end()));
  return best;
}

TEST(ExactTour, EqualsTheBestOfEveryPermutation) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    for (const bool closed : {true, false}) {
      const int n = 2 + static_cast<int>(seed % 7);  // 2..8 stops
      const CostMatrix c = RandomInstance(n, seed, seed % 2 == 0);
      const std::vector<int> order = ExactTour(c, closed);
      ASSERT_TRUE(IsTourFromZero(order, n));
      EXPECT_NEAR(TourCost(c, order, closed), BruteForceOptimum(c, closed), 1e-9)
          << "seed " << seed << (closed ? " closed" : " open");
    }
  }
}

// The bound: within 10 % of the optimum on instances small enough to solve exactly
// (here up to 10 targets + the start). Measured worst ratio over these 200 instances is
// printed; 1.10 is the bound asserted.
TEST(ImproveTour, HeuristicStaysWithinTenPercentOfTheOptimum) {
  double worst = 1.0, sum = 0.0;
  int instances = 0;
  for (unsigned seed = 1; seed <= 50; ++seed) {
    for (const bool closed : {true, false}) {
      for (const bool clustered : {false, true}) {
        const int n = 4 + static_cast<int>(seed % 8);  // 3..10 targets + the start
        const CostMatrix c = RandomInstance(n, 1000 + seed, clustered);
        std::vector<int> order = NearestNeighbourTour(c);
        ImproveTour(c, closed, &order);
        ASSERT_TRUE(IsTourFromZero(order, n));
        const double optimum = TourCost(c, ExactTour(c, closed), closed);
        const double ratio = TourCost(c, order, closed) / optimum;
        EXPECT_LE(ratio, 1.10) << "seed " << seed << " n " << n;
        EXPECT_GE(ratio, 1.0 - 1e-9);
        worst = std::max(worst, ratio);
        sum += ratio;
        ++instances;
      }
    }
  }
  std::printf("heuristic / optimum over %d instances: mean %.4f, worst %.4f\n", instances,
              sum / instances, worst);
}

TEST(ImproveTour, NeverLengthensATourAndKeepsTheStartFirst) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const CostMatrix c = RandomInstance(40, seed, false);
    std::vector<int> order(40);
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin() + 1, order.end(), std::mt19937(seed));
    for (const bool closed : {true, false}) {
      std::vector<int> improved = order;
      ImproveTour(c, closed, &improved);
      ASSERT_TRUE(IsTourFromZero(improved, 40));
      EXPECT_LE(TourCost(c, improved, closed), TourCost(c, order, closed) + 1e-9);
    }
  }
}

TEST(PlanTour, UsesHeldKarpUpToTheLimitAndTheHeuristicBeyond) {
  TourOptions options;
  options.exact_max_stops = 6;
  TourMethod method;
  EXPECT_TRUE(IsTourFromZero(PlanTour(RandomInstance(7, 3, false), options, &method), 7));
  EXPECT_EQ(method, TourMethod::kExact);
  EXPECT_TRUE(IsTourFromZero(PlanTour(RandomInstance(8, 3, false), options, &method), 8));
  EXPECT_EQ(method, TourMethod::kHeuristic);
  EXPECT_EQ(PlanTour(CostMatrix::Zero(1, 1), options, &method), std::vector<int>{0});
  EXPECT_EQ(method, TourMethod::kTrivial);
  // Open with two stops: the nearer first.
  CostMatrix c(3, 3);
  c << 0, 5, 2, 5, 0, 4, 2, 4, 0;
  options.return_to_start = false;
  EXPECT_EQ(PlanTour(c, options), (std::vector<int>{0, 2, 1}));
}

TEST(TourOptions, ValidationNamesTheField) {
  TourOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.exact_max_stops = 17;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("exact_max_stops = 17"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::inspection
