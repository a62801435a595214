#pragma once
// Small shared pieces of the map benchmark: a CPU clock, heap accounting and a report that
// prints as a table and writes as JSON ({section: {key: number}}).

#include <malloc.h>
#include <time.h>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace hylo::benchmarks {

/// CPU time of the calling thread, ms. Every index here runs on the calling thread, so on an
/// idle machine this equals wall time, and on a shared one it is not inflated by waiting.
inline double NowMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

/// Bytes currently allocated through malloc (small blocks + mmapped blocks), glibc.
inline std::size_t HeapBytes() {
  const struct mallinfo2 info = mallinfo2();
  return info.uordblks + info.hblkhd;
}

class Report {
 public:
  void Set(const std::string& section, const std::string& key, double value) {
    for (auto& [name, entries] : sections_) {
      if (name == section) {
        entries.emplace_back(key, value);
        return;
      }
    }
    sections_.push_back({section, {{key, value}}});
  }

  /// A value set earlier (NaN when absent).
  double Get(const std::string& section, const std::string& key) const {
    for (const auto& [name, entries] : sections_) {
      for (const auto& [k, value] : entries) {
        if (name == section && k == key) return value;
      }
    }
    return std::nan("");
  }

  void Print(std::ostream& os) const {
    for (const auto& [name, entries] : sections_) {
      os << "\n== " << name << "\n";
      for (const auto& [key, value] : entries) {
        os << "  " << std::left << std::setw(44) << key << std::right << std::setw(14) << std::fixed
           << std::setprecision(4) << value << "\n";
      }
    }
  }

  bool WriteJson(const std::string& path) const {
    std::ofstream out(path);
    out << "{\n";
    for (std::size_t s = 0; s < sections_.size(); ++s) {
      out << "  \"" << sections_[s].first << "\": {\n";
      const auto& entries = sections_[s].second;
      for (std::size_t i = 0; i < entries.size(); ++i) {
        out << "    \"" << entries[i].first << "\": ";
        if (std::isfinite(entries[i].second)) {
          out << std::setprecision(9) << entries[i].second;
        } else {
          out << "null";  // JSON has no inf/NaN
        }
        out << (i + 1 < entries.size() ? ",\n" : "\n");
      }
      out << "  }" << (s + 1 < sections_.size() ? ",\n" : "\n");
    }
    out << "}\n";
    return static_cast<bool>(out);
  }

 private:
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, double>>>> sections_;
};

}  // namespace hylo::benchmarks
