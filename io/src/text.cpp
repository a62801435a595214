#include "hylo/io/text.h"

#include <cctype>
#include <sstream>
#include <stdexcept>

namespace hylo::io {

void ThrowFileError(const std::string& path, const std::string& reason) {
  throw std::runtime_error(path + ": " + reason);
}

std::string ToLower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::vector<std::string> SplitWords(const std::string& line) {
  std::vector<std::string> words;
  std::istringstream stream(line);
  std::string word;
  while (stream >> word) words.push_back(word);
  return words;
}

}  // namespace hylo::io
