#pragma once
// What the CSV and YAML target readers share (private to hylo_io): the keys, how a value
// lands in a Target, and the checks every target gets once its fields are read.

#include <map>
#include <set>
#include <string>

#include "hylo/inspection/target.h"

namespace hylo::io::targets {

enum class Key {
  kId, kX, kY, kZ, kMinRange, kMaxRange, kSizeX, kSizeY, kSizeZ, kAzimuth, kTolerance
};

/// The key named `name` into *key; false for an unknown name.
bool KeyOf(const std::string& name, Key* key);
/// Every key's name, for "expected one of" messages.
std::string KeyNames();
const char* NameOf(Key key);

/// Parses `text` as a finite number into *value; false when it is not one.
bool ParseFinite(const std::string& text, double* value);
/// Stores a number read for `key` (not kId).
void Assign(Key key, double value, inspection::Target* target);

/// `text` with control characters as '?' (it goes into a one-line error).
std::string Printable(std::string text);

/// Checks a target whose `given` keys were read at `where` ("line 7"): required keys,
/// complete groups (the box, the viewing direction), a usable and new id (`first_seen` maps
/// ids to where they were read), Target::IsValid. Throws std::runtime_error
/// "<path>: <where>: <reason>".
void Finish(const std::string& path, const std::string& where, const std::set<Key>& given,
            const inspection::Target& target, std::map<std::string, std::string>* first_seen);

}  // namespace hylo::io::targets
