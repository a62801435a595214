#pragma once
// Helpers for the cloud file tests: random clouds and raw files written byte by byte.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "hylo/io/cloud_io.h"

namespace hylo::io::testing {

/// A random cloud around `center` with every attribute filled, fixed seed.
inline CloudFile RandomCloud(std::size_t n, const Eigen::Vector3d& center, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-50.0, 50.0);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  std::uniform_int_distribution<int32_t> label(-5, 1000000);
  CloudFile cloud;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.positions.push_back(center + Eigen::Vector3d(coord(rng), coord(rng), coord(rng)));
    cloud.intensity.push_back(100.f * (unit(rng) + 1.f));
    cloud.normals.push_back(Eigen::Vector3f(unit(rng), unit(rng), unit(rng)).normalized());
    cloud.labels.push_back(label(rng));
  }
  return cloud;
}

/// Each coordinate rounded to float and back (what a float32 file field stores).
/// Test-name suffix for an encoding-parameterised suite.
inline std::string EncodingName(CloudEncoding encoding) {
  switch (encoding) {
    case CloudEncoding::kAscii: return "ascii";
    case CloudEncoding::kBinary: return "binary";
    case CloudEncoding::kBinaryCompressed: return "binary_compressed";
  }
  return "unknown";
}

inline Eigen::Vector3d RoundToFloat(const Eigen::Vector3d& p) {
  return Eigen::Vector3d(static_cast<float>(p.x()), static_cast<float>(p.y()),
                         static_cast<float>(p.z()));
}

/// Writes `text` followed by `bytes`.
inline void WriteRaw(const std::string& path, const std::string& text,
                     const std::vector<uint8_t>& bytes = {}) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

template <typename T>
void Append(std::vector<uint8_t>* out, T value, bool big_endian = false) {
  const auto* p = reinterpret_cast<const uint8_t*>(&value);
  std::vector<uint8_t> b(p, p + sizeof(T));
  if (big_endian) std::reverse(b.begin(), b.end());
  out->insert(out->end(), b.begin(), b.end());
}

/// Expects ReadCloud(path) to throw an error that names the file and contains `fragment`.
inline void ExpectReadError(const std::string& path, const std::string& fragment) {
  try {
    ReadCloud(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

inline std::size_t FileSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  return static_cast<std::size_t>(in.tellg());
}

/// Copies the first `keep` bytes of `from` into `to`.
inline void Truncate(const std::string& from, const std::string& to, std::size_t keep) {
  std::ifstream in(from, std::ios::binary);
  std::vector<char> bytes(keep);
  in.read(bytes.data(), static_cast<std::streamsize>(keep));
  std::ofstream out(to, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(keep));
}

}  // namespace hylo::io::testing
