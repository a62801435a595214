#pragma once
// The order of visits: a travelling-salesman tour over the stops (stop 0 = the start) on a
// symmetric matrix of travel costs, closed (back to the start) or open (ends at the last stop).
//   - exact for small instances: Held-Karp dynamic programming over subsets, O(2^n n^2)
//     (Held & Karp, "A Dynamic Programming Approach to Sequencing Problems", 1962);
//   - otherwise nearest neighbour from the start, then 2-opt (reverse a stretch) and Or-opt
//     (move a run of 1-3 stops elsewhere, either way round) until neither improves.
// An open tour is solved as a closed one with a dummy stop joined to the start at cost 0 and
// to every other stop at one large equal cost: every closed tour through it pays that cost
// once, so the best one is the best open path from the start, and one improvement code serves
// both.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace hylo::inspection {

/// Travel costs between stops, symmetric, finite, zero diagonal; stop 0 is the start.
using CostMatrix = Eigen::MatrixXd;

struct TourOptions {
  bool return_to_start = true;  ///< closed tour (back to the start) or open (ends at the last
                                ///< viewpoint)
  int exact_max_stops = 12;     ///< Held-Karp when there are at most this many stops besides
                                ///< the start (0..16: memory is 2^n n doubles), else heuristic

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
};

/// Cost of visiting `order` (a permutation of 0..n-1 starting with 0), back to 0 when closed.
double TourCost(const CostMatrix& cost, const std::vector<int>& order, bool closed);

/// Nearest neighbour from stop 0.
std::vector<int> NearestNeighbourTour(const CostMatrix& cost);

/// 2-opt and Or-opt moves until none improves; `order` starts with 0 and keeps it first.
void ImproveTour(const CostMatrix& cost, bool closed, std::vector<int>* order);

/// The optimal order (Held-Karp). Needs cost.rows() - 1 <= 20.
std::vector<int> ExactTour(const CostMatrix& cost, bool closed);

/// Which solver ran.
enum class TourMethod { kTrivial, kExact, kHeuristic };
const char* TourMethodName(TourMethod method);

/// The order of visits: exact when small enough, else nearest neighbour + improvement.
std::vector<int> PlanTour(const CostMatrix& cost, const TourOptions& options,
                          TourMethod* method = nullptr);

}  // namespace hylo::inspection
