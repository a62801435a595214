#pragma once
// Private to hylo_io: the LogReader of a bag whose index rosbag cannot read (recording killed,
// file cut short), read record by record up to its last complete message.

#include <memory>
#include <string>

#include "hylo/logs/log_reader.h"

namespace hylo::logs::detail {

/// `damage` says what is wrong with the bag (LogRecovery::damage). Throws like OpenBag when a
/// topic is missing or of the wrong type among the records that can be read.
std::unique_ptr<LogReader> OpenRecoveredBag(const std::string& path, const LogReadOptions& options,
                                            const std::string& damage);

}  // namespace hylo::logs::detail
