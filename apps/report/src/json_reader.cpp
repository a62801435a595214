// A recursive-descent JSON reader (RFC 8259) producing io::Json values.
#include "hylo/report/json_reader.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace hylo::report {
namespace {

class Parser {
 public:
  Parser(const std::string& text, const std::string& source) : text_(text), source_(source) {}

  io::Json ParseDocument() {
    io::Json value = ParseValue(0);
    SkipSpace();
    if (pos_ != text_.size()) Fail("trailing text after the JSON value");
    return value;
  }

 private:
  static constexpr int kMaxDepth = 256;  // guards the stack against hostile nesting

  [[noreturn]] void Fail(const std::string& why) const {
    throw std::runtime_error(source_ + ": JSON error at byte " + std::to_string(pos_) + ": " + why);
  }
  void SkipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  bool Consume(char c) {
    SkipSpace();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  void Expect(char c) {
    if (!Consume(c)) Fail(std::string("expected '") + c + "'");
  }
  bool ConsumeWord(const char* word) {
    const std::string w(word);
    if (text_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }

  io::Json ParseValue(int depth) {
    if (depth > kMaxDepth) Fail("nesting deeper than 256");
    SkipSpace();
    if (pos_ >= text_.size()) Fail("unexpected end of text");
    const char c = text_[pos_];
    if (c == '{') return ParseObject(depth);
    if (c == '[') return ParseArray(depth);
    if (c == '"') return io::Json(ParseString());
    if (ConsumeWord("true")) return io::Json(true);
    if (ConsumeWord("false")) return io::Json(false);
    if (ConsumeWord("null")) return io::Json();
    if (c == '-' || std::isdigit(static_cast<unsigned char>(c))) return ParseNumber();
    Fail(std::string("unexpected character '") + c + "'");
  }

  io::Json ParseObject(int depth) {
    Expect('{');
    io::Json object = io::Json::MakeObject();
    if (Consume('}')) return object;
    do {
      SkipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '"') Fail("expected a member name");
      const std::string key = ParseString();
      Expect(':');
      object[key] = ParseValue(depth + 1);
    } while (Consume(','));
    Expect('}');
    return object;
  }

  io::Json ParseArray(int depth) {
    Expect('[');
    io::Json array = io::Json::MakeArray();
    if (Consume(']')) return array;
    do {
      array.PushBack(ParseValue(depth + 1));
    } while (Consume(','));
    Expect(']');
    return array;
  }

  // Appends code point `cp` as UTF-8.
  static void AppendUtf8(uint32_t cp, std::string* out) {
    if (cp < 0x80) {
      out->push_back(static_cast<char>(cp));
    } else if (cp < 0x800) {
      out->push_back(static_cast<char>(0xC0 | (cp >> 6)));
      out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
    } else if (cp < 0x10000) {
      out->push_back(static_cast<char>(0xE0 | (cp >> 12)));
      out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
      out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
    } else {
      out->push_back(static_cast<char>(0xF0 | (cp >> 18)));
      out->push_back(static_cast<char>(0x80 | ((cp >> 12) & 0x3F)));
      out->push_back(static_cast<char>(0x80 | ((cp >> 6) & 0x3F)));
      out->push_back(static_cast<char>(0x80 | (cp & 0x3F)));
    }
  }

  uint32_t ParseHex4() {
    if (pos_ + 4 > text_.size()) Fail("truncated \\u escape");
    uint32_t cp = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = text_[pos_++];
      if (!std::isxdigit(static_cast<unsigned char>(h))) Fail("bad hex digit in \\u escape");
      cp = cp * 16 + static_cast<uint32_t>(std::isdigit(static_cast<unsigned char>(h))
                                               ? h - '0'
                                               : std::tolower(h) - 'a' + 10);
    }
    return cp;
  }

  std::string ParseString() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= text_.size()) Fail("unterminated string");
      const char c = text_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) Fail("control character in a string");
      if (c != '\\') {
        out.push_back(c);
        continue;
      }
      if (pos_ >= text_.size()) Fail("unterminated escape");
      const char e = text_[pos_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out.push_back(e);
          break;
        case 'b':
          out.push_back('\b');
          break;
        case 'f':
          out.push_back('\f');
          break;
        case 'n':
          out.push_back('\n');
          break;
        case 'r':
          out.push_back('\r');
          break;
        case 't':
          out.push_back('\t');
          break;
        case 'u': {
          uint32_t cp = ParseHex4();
          // A surrogate pair encodes one code point above U+FFFF.
          if (cp >= 0xD800 && cp < 0xDC00 && ConsumeWord("\\u")) {
            const uint32_t low = ParseHex4();
            if (low < 0xDC00 || low >= 0xE000) Fail("bad low surrogate");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
          }
          AppendUtf8(cp, &out);
          break;
        }
        default:
          Fail(std::string("bad escape '\\") + e + "'");
      }
    }
  }

  io::Json ParseNumber() {
    const std::size_t start = pos_;
    bool integral = true;
    if (text_[pos_] == '-') ++pos_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-') {
        integral = false;
      } else if (!std::isdigit(static_cast<unsigned char>(c))) {
        break;
      }
      ++pos_;
    }
    const std::string number = text_.substr(start, pos_ - start);
    char* end = nullptr;
    if (integral && number.size() < 19) {
      const long long v = std::strtoll(number.c_str(), &end, 10);
      if (end != nullptr && *end == '\0' && number != "-") return io::Json(v);
    }
    const double v = std::strtod(number.c_str(), &end);
    if (end == nullptr || *end != '\0' || number.empty() || number == "-") {
      pos_ = start;
      Fail("malformed number '" + number + "'");
    }
    return io::Json(v);
  }

  const std::string& text_;
  const std::string& source_;
  std::size_t pos_ = 0;
};

}  // namespace

io::Json ParseJson(const std::string& text, const std::string& source_name) {
  return Parser(text, source_name).ParseDocument();
}

io::Json ReadJsonFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("'" + path + "': cannot open (missing or unreadable)");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseJson(text.str(), path);
}

double NumberAt(const io::Json& json, const std::string& dotted_path) {
  const io::Json* node = &json;
  std::size_t begin = 0;
  while (node != nullptr && begin <= dotted_path.size()) {
    const std::size_t dot = dotted_path.find('.', begin);
    const std::string key = dotted_path.substr(begin, dot - begin);
    node = node->Find(key);
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return node == nullptr ? nan : node->AsNumber(nan);
}

}  // namespace hylo::report
