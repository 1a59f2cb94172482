#pragma once
// A small JSON reader for tests that parse the program's --format json output (RFC 8259 values;
// \u escapes are kept as text, which the program never writes). Throws std::runtime_error on
// malformed input.
#include <cctype>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace testing_support {

struct Json {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  bool boolean = false;
  double number = 0;
  std::string text;
  std::vector<Json> items;            // array
  std::map<std::string, Json> members;  // object

  bool has(const std::string& key) const { return type == Type::object && members.count(key) != 0; }
  const Json& operator[](const std::string& key) const {
    const auto it = members.find(key);
    if (type != Type::object || it == members.end()) throw std::runtime_error("JSON: no key \"" + key + "\"");
    return it->second;
  }
  const Json& operator[](std::size_t index) const { return items.at(index); }
  std::size_t size() const { return type == Type::array ? items.size() : members.size(); }
  std::vector<double> numbers() const {
    std::vector<double> out;
    for (const Json& item : items) out.push_back(item.number);
    return out;
  }
};

namespace json_detail {

class Reader {
public:
  explicit Reader(const std::string& text) : s_(text) {}

  Json document() {
    Json value = parse();
    skip();
    if (at_ != s_.size()) fail("trailing text");
    return value;
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("JSON: " + what + " at offset " + std::to_string(at_));
  }
  void skip() {
    while (at_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[at_]))) ++at_;
  }
  bool take(char c) {
    skip();
    if (at_ < s_.size() && s_[at_] == c) return ++at_, true;
    return false;
  }
  void expect(char c) {
    if (!take(c)) fail(std::string("expected '") + c + "'");
  }
  bool word(const char* w) {
    const std::string t(w);
    if (s_.compare(at_, t.size(), t) != 0) return false;
    at_ += t.size();
    return true;
  }
  std::string string() {
    expect('"');
    std::string out;
    while (at_ < s_.size() && s_[at_] != '"') {
      if (s_[at_] == '\\' && at_ + 1 < s_.size()) {
        const char e = s_[++at_];
        out += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'u' ? 'u' : e;
      } else {
        out += s_[at_];
      }
      ++at_;
    }
    if (at_ == s_.size()) fail("unterminated string");
    ++at_;
    return out;
  }
  Json parse() {
    skip();
    if (at_ == s_.size()) fail("unexpected end");
    Json v;
    const char c = s_[at_];
    if (c == '{') {
      ++at_;
      v.type = Json::Type::object;
      if (take('}')) return v;
      do {
        skip();
        const std::string key = string();
        expect(':');
        v.members[key] = parse();
      } while (take(','));
      expect('}');
    } else if (c == '[') {
      ++at_;
      v.type = Json::Type::array;
      if (take(']')) return v;
      do v.items.push_back(parse());
      while (take(','));
      expect(']');
    } else if (c == '"') {
      v.type = Json::Type::string;
      v.text = string();
    } else if (word("true") || word("false")) {
      v.type = Json::Type::boolean;
      v.boolean = s_[at_ - 1] == 'e' && s_[at_ - 2] == 'u';
    } else if (word("null")) {
      v.type = Json::Type::null;
    } else {
      char* end = nullptr;
      v.type = Json::Type::number;
      v.number = std::strtod(s_.c_str() + at_, &end);
      if (end == s_.c_str() + at_) fail("not a value");
      at_ = static_cast<std::size_t>(end - s_.c_str());
    }
    return v;
  }

  const std::string& s_;
  std::size_t at_ = 0;
};

}  // namespace json_detail

inline Json parse_json(const std::string& text) { return json_detail::Reader(text).document(); }

}  // namespace testing_support
