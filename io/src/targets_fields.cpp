#include "targets_fields.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <utility>

#include "hylo/io/targets_io.h"
#include "hylo/io/text.h"

namespace hylo::io::targets {
namespace {

constexpr std::pair<Key, const char*> kKeys[] = {
    {Key::kId, "id"},
    {Key::kX, "x"},
    {Key::kY, "y"},
    {Key::kZ, "z"},
    {Key::kMinRange, "min_range_m"},
    {Key::kMaxRange, "max_range_m"},
    {Key::kSizeX, "size_x"},
    {Key::kSizeY, "size_y"},
    {Key::kSizeZ, "size_z"},
    {Key::kAzimuth, "view_azimuth_deg"},
    {Key::kTolerance, "view_tolerance_deg"},
};

// Keys that come all together or not at all.
bool PartialGroup(const std::set<Key>& given, std::initializer_list<Key> group) {
  std::size_t n = 0;
  for (const Key k : group) n += given.count(k);
  return n != 0 && n != group.size();
}

}  // namespace

bool KeyOf(const std::string& name, Key* key) {
  for (const auto& [k, n] : kKeys) {
    if (name == n) {
      *key = k;
      return true;
    }
  }
  return false;
}

const char* NameOf(Key key) {
  for (const auto& [k, n] : kKeys) {
    if (k == key) return n;
  }
  return "?";
}

std::string KeyNames() {
  std::string names;
  for (const auto& [k, n] : kKeys) names += (names.empty() ? "" : ", ") + std::string(n);
  return names;
}

bool ParseFinite(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

void Assign(Key key, double value, inspection::Target* t) {
  switch (key) {
    case Key::kX: t->position.x() = value; break;
    case Key::kY: t->position.y() = value; break;
    case Key::kZ: t->position.z() = value; break;
    case Key::kMinRange: t->min_range_m = value; break;
    case Key::kMaxRange: t->max_range_m = value; break;
    case Key::kSizeX: t->box_size_m.x() = value; break;
    case Key::kSizeY: t->box_size_m.y() = value; break;
    case Key::kSizeZ: t->box_size_m.z() = value; break;
    case Key::kAzimuth: t->view_azimuth_deg = value; break;
    case Key::kTolerance: t->view_tolerance_deg = value; break;
    case Key::kId: break;
  }
}

std::string Printable(std::string text) {
  for (char& c : text) {
    if (std::iscntrl(static_cast<unsigned char>(c))) c = '?';
  }
  return text;
}

void Finish(const std::string& path, const std::string& where, const std::set<Key>& given,
            const inspection::Target& target, std::map<std::string, std::string>* first_seen) {
  const auto fail = [&](const std::string& reason) { ThrowFileError(path, where + ": " + reason); };
  for (const Key k : {Key::kId, Key::kX, Key::kY, Key::kZ}) {
    if (!given.count(k)) fail(std::string("missing ") + NameOf(k));
  }
  if (PartialGroup(given, {Key::kSizeX, Key::kSizeY, Key::kSizeZ}))
    fail("size_x, size_y and size_z go together (a box) or not at all");
  if (PartialGroup(given, {Key::kAzimuth, Key::kTolerance}))
    fail("view_azimuth_deg and view_tolerance_deg go together or not at all");
  if (!IsValidTargetId(target.id)) {
    fail("id '" + Printable(target.id) +
         "' must be 1-64 letters, digits, '_', '-' or '.', starting with a letter, digit or '_' "
         "(it names a file)");
  }
  const auto [it, added] = first_seen->emplace(target.id, where);
  if (!added) fail("id '" + target.id + "' given twice (first at " + it->second + ")");
  std::string why;
  if (!target.IsValid(&why)) fail("target '" + target.id + "': " + why);
}

}  // namespace hylo::io::targets
