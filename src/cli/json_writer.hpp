#pragma once
// A minimal streaming JSON writer: objects, arrays, strings, numbers (shortest round-trip form),
// booleans. A non-finite number is a bug upstream and throws rather than printing NaN.
#include <string>
#include <vector>

namespace bladestab::cli {

class JsonWriter {
public:
  JsonWriter& begin_object(const char* key = nullptr);
  JsonWriter& end_object();
  JsonWriter& begin_array(const char* key = nullptr);
  JsonWriter& end_array();
  JsonWriter& value(const char* key, double v);
  JsonWriter& value(const char* key, int v);
  JsonWriter& value(const char* key, bool v);
  JsonWriter& value(const char* key, const std::string& v);
  JsonWriter& value(const char* key, const char* v) { return value(key, std::string(v)); }
  JsonWriter& null_value(const char* key);
  JsonWriter& element(double v) { return value(nullptr, v); }
  JsonWriter& element(int v) { return value(nullptr, v); }
  JsonWriter& numbers(const char* key, const std::vector<double>& values);
  JsonWriter& numbers(const char* key, const std::vector<int>& values);
  // Like numbers(), but NaN stands for "no value" and is written as null.
  JsonWriter& numbers_or_null(const char* key, const std::vector<double>& values);

  const std::string& str() const { return out_; }

private:
  void prefix(const char* key);
  std::string out_;
  std::vector<bool> first_;  // per open container: no element written yet
};

}  // namespace bladestab::cli
