#include "hylo/inspection/tour.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"

namespace hylo::inspection {
namespace {

constexpr double kImprovement = 1e-9;  // smaller gains are rounding, not progress

// One pass of 2-opt on a closed tour (position 0 fixed): reverse order[i..j] when that
// shortens it. True when something changed.
bool TwoOptPass(const CostMatrix& c, std::vector<int>* order) {
  std::vector<int>& t = *order;
  const int n = static_cast<int>(t.size());
  bool improved = false;
  for (int i = 1; i + 1 < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const int a = t[i - 1], b = t[i], d = t[j], e = t[(j + 1) % n];
      const double delta = c(a, d) + c(b, e) - c(a, b) - c(d, e);
      if (delta < -kImprovement) {
        std::reverse(t.begin() + i, t.begin() + j + 1);
        improved = true;
      }
    }
  }
  return improved;
}

// One pass of Or-opt on a closed tour: move the run order[i..i+len) between two other
// neighbours, forwards or reversed, when that shortens it.
bool OrOptPass(const CostMatrix& c, std::vector<int>* order) {
  std::vector<int>& t = *order;
  const int n = static_cast<int>(t.size());
  bool improved = false;
  for (int len = 1; len <= 3; ++len) {
    for (int i = 1; i + len <= n; ++i) {
      const int prev = t[i - 1], first = t[i], last = t[i + len - 1], next = t[(i + len) % n];
      const double removed = c(prev, first) + c(last, next) - c(prev, next);
      std::vector<int> rest(t.begin(), t.begin() + i);
      rest.insert(rest.end(), t.begin() + i + len, t.end());
      const int m = static_cast<int>(rest.size());
      double best = -kImprovement;
      int best_k = -1;
      bool best_reversed = false;
      for (int k = 0; k < m; ++k) {  // between rest[k] and rest[k + 1]
        const int p = rest[k], q = rest[(k + 1) % m];
        const double forward = c(p, first) + c(last, q) - c(p, q) - removed;
        const double reversed = c(p, last) + c(first, q) - c(p, q) - removed;
        if (forward < best) best = forward, best_k = k, best_reversed = false;
        if (reversed < best) best = reversed, best_k = k, best_reversed = true;
      }
      if (best_k < 0) continue;
      std::vector<int> run(t.begin() + i, t.begin() + i + len);
      if (best_reversed) std::reverse(run.begin(), run.end());
      rest.insert(rest.begin() + best_k + 1, run.begin(), run.end());
      t = rest;
      improved = true;
    }
  }
  return improved;
}

// The matrix with a dummy stop (index n) that turns an open path from 0 into a closed tour.
CostMatrix WithDummyStop(const CostMatrix& cost) {
  const int n = static_cast<int>(cost.rows());
  const double big = 1.0 + cost.cwiseAbs().sum();
  CostMatrix c = CostMatrix::Constant(n + 1, n + 1, 0.0);
  c.topLeftCorner(n, n) = cost;
  for (int j = 1; j < n; ++j) c(n, j) = c(j, n) = big;
  return c;
}

}  // namespace

bool TourOptions::IsValid(std::string* why) const {
  return (exact_max_stops >= 0 && exact_max_stops <= 16) ||
         FailOption("exact_max_stops", exact_max_stops, "must be in [0, 16]", why);
}

double TourCost(const CostMatrix& cost, const std::vector<int>& order, bool closed) {
  double total = 0.0;
  for (std::size_t i = 1; i < order.size(); ++i) total += cost(order[i - 1], order[i]);
  if (closed && order.size() > 1) total += cost(order.back(), order.front());
  return total;
}

std::vector<int> NearestNeighbourTour(const CostMatrix& cost) {
  const int n = static_cast<int>(cost.rows());
  std::vector<int> order{0};
  std::vector<bool> used(n, false);
  used[0] = true;
  for (int step = 1; step < n; ++step) {
    int best = -1;
    for (int j = 0; j < n; ++j) {
      if (!used[j] && (best < 0 || cost(order.back(), j) < cost(order.back(), best))) best = j;
    }
    used[best] = true;
    order.push_back(best);
  }
  return order;
}

void ImproveTour(const CostMatrix& cost, bool closed, std::vector<int>* order) {
  HYLO_CHECK(!order->empty() && order->front() == 0, "a tour starts at stop 0");
  const int n = static_cast<int>(cost.rows());
  if (n < 3) return;
  const CostMatrix c = closed ? cost : WithDummyStop(cost);
  std::vector<int> t = *order;
  if (!closed) t.push_back(n);  // the dummy closes the path back to 0
  for (int round = 0; round < 1000; ++round) {
    const bool two_opt = TwoOptPass(c, &t);
    const bool or_opt = OrOptPass(c, &t);
    if (!two_opt && !or_opt) break;
  }
  if (!closed) {
    // The dummy sits next to 0 (any other neighbour costs `big` once more); read the path
    // from 0 away from it.
    const int at = static_cast<int>(std::find(t.begin(), t.end(), n) - t.begin());
    const bool dummy_before_zero = t[(at + 1) % t.size()] == 0;
    std::vector<int> path;
    for (std::size_t k = 1; k < t.size(); ++k) {
      const std::size_t i = dummy_before_zero ? (at + k) % t.size() : (at + t.size() - k) % t.size();
      path.push_back(t[i]);
    }
    t = path;
  }
  *order = t;
}

std::vector<int> ExactTour(const CostMatrix& cost, bool closed) {
  const int n = static_cast<int>(cost.rows());
  HYLO_CHECK(n >= 1 && n - 1 <= 20, "Held-Karp is for small instances");
  const int m = n - 1;  // stops besides the start, bit k = stop k + 1
  if (m == 0) return {0};
  const std::size_t subsets = std::size_t{1} << m;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> best(subsets * m, kInf);  // [subset][last]: 0 -> subset, ending at last
  std::vector<int> from(subsets * m, -1);
  for (int k = 0; k < m; ++k) best[(std::size_t{1} << k) * m + k] = cost(0, k + 1);
  for (std::size_t s = 1; s < subsets; ++s) {
    for (int last = 0; last < m; ++last) {
      const double here = best[s * m + last];
      if (!(s >> last & 1) || here == kInf) continue;
      for (int next = 0; next < m; ++next) {
        if (s >> next & 1) continue;
        const std::size_t t = s | (std::size_t{1} << next);
        const double via = here + cost(last + 1, next + 1);
        if (via < best[t * m + next]) {
          best[t * m + next] = via;
          from[t * m + next] = last;
        }
      }
    }
  }
  const std::size_t all = subsets - 1;
  int last = 0;
  for (int k = 1; k < m; ++k) {
    const double a = best[all * m + k] + (closed ? cost(k + 1, 0) : 0.0);
    const double b = best[all * m + last] + (closed ? cost(last + 1, 0) : 0.0);
    if (a < b) last = k;
  }
  std::vector<int> order;
  for (std::size_t s = all; last >= 0;) {
    order.push_back(last + 1);
    const int previous = from[s * m + last];
    s &= ~(std::size_t{1} << last);
    last = previous;
  }
  order.push_back(0);
  std::reverse(order.begin(), order.end());
  return order;
}

const char* TourMethodName(TourMethod method) {
  switch (method) {
    case TourMethod::kTrivial: return "trivial";
    case TourMethod::kExact: return "exact";
    case TourMethod::kHeuristic: return "nearest_neighbour_2opt_oropt";
  }
  return "unknown";
}

std::vector<int> PlanTour(const CostMatrix& cost, const TourOptions& options, TourMethod* method) {
  const int n = static_cast<int>(cost.rows());
  TourMethod used = TourMethod::kHeuristic;
  std::vector<int> order;
  if (n <= 3) {
    used = TourMethod::kTrivial;  // every order of two stops costs the same when closed
    order = n <= 0 ? std::vector<int>{} : NearestNeighbourTour(cost);
    if (!options.return_to_start && n == 3 && cost(0, 2) < cost(0, 1)) order = {0, 2, 1};
  } else if (n - 1 <= options.exact_max_stops) {
    used = TourMethod::kExact;
    order = ExactTour(cost, options.return_to_start);
  } else {
    order = NearestNeighbourTour(cost);
    ImproveTour(cost, options.return_to_start, &order);
  }
  if (method != nullptr) *method = used;
  return order;
}

}  // namespace hylo::inspection
