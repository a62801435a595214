#pragma once
// The enums a configuration names, one table each: every value a file may give, in the order
// error messages and docs/configuration.md list them. Names come from the owning library's
// ToString and are parsed by its Parse function, so a name is spelled in one place; the value
// lists here are what the reader's "expected ..." messages and the reference doc both print.

#include <string>
#include <vector>

#include "hylo/config/run_config.h"

namespace hylo::config {

template <class E>
struct EnumField;  // defined for every enum the field list holds

template <>
struct EnumField<logs::PointTimeConvention> {
  using E = logs::PointTimeConvention;
  static std::vector<E> Values() {
    return {E::kAuto, E::kVelodyne, E::kOuster, E::kHesai, E::kRobosense, E::kLivox, E::kNone};
  }
  static std::string Name(E e) { return logs::ToString(e); }
  static bool Parse(const std::string& s, E* e) { return logs::ParsePointTimeConvention(s, e); }
};

template <>
struct EnumField<estimation::Estimator::Backend> {
  using E = estimation::Estimator::Backend;
  static std::vector<E> Values() { return {E::kIeskf, E::kSlidingWindow}; }
  static std::string Name(E e) { return estimation::ToString(e); }
  static bool Parse(const std::string& s, E* e) { return estimation::ParseBackend(s, e); }
};

template <>
struct EnumField<estimation::SlidingWindowOptions::LinearSolver> {
  using E = estimation::SlidingWindowOptions::LinearSolver;
  static std::vector<E> Values() {
    return {E::kSparseNormalCholesky, E::kDenseNormalCholesky, E::kDenseSchur, E::kSparseSchur,
            E::kDenseQr};
  }
  static std::string Name(E e) { return estimation::ToString(e); }
  static bool Parse(const std::string& s, E* e) { return estimation::ParseLinearSolver(s, e); }
};

template <>
struct EnumField<estimation::SlidingWindowOptions::RobustLoss> {
  using E = estimation::SlidingWindowOptions::RobustLoss;
  static std::vector<E> Values() { return {E::kNone, E::kHuber, E::kCauchy, E::kGemanMcClure}; }
  static std::string Name(E e) { return estimation::ToString(e); }
  static bool Parse(const std::string& s, E* e) { return estimation::ParseRobustLoss(s, e); }
};

template <>
struct EnumField<terrain::GroundMethod> {
  using E = terrain::GroundMethod;
  static std::vector<E> Values() { return {E::kSmrf, E::kCsf}; }
  static std::string Name(E e) { return terrain::ToString(e); }
  static bool Parse(const std::string& s, E* e) { return terrain::ParseGroundMethod(s, e); }
};

template <>
struct EnumField<terrain::ClothHoleFill> {
  using E = terrain::ClothHoleFill;
  static std::vector<E> Values() { return {E::kNeighbourMean, E::kNearest, E::kReferenceScanline}; }
  static std::string Name(E e) { return terrain::ToString(e); }
  static bool Parse(const std::string& s, E* e) { return terrain::ParseClothHoleFill(s, e); }
};

/// The names of every value of E, e.g. {"ieskf", "sliding_window"}.
template <class E>
std::vector<std::string> EnumNames() {
  std::vector<std::string> names;
  for (E e : EnumField<E>::Values()) names.push_back(EnumField<E>::Name(e));
  return names;
}

/// "a, b or c".
inline std::string JoinAlternatives(const std::vector<std::string>& names) {
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) list += i + 1 == names.size() ? " or " : ", ";
    list += names[i];
  }
  return list;
}

}  // namespace hylo::config
