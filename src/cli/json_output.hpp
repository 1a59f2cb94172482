#pragma once
// The program's JSON documents are nlohmann::ordered_json values, their keys in the order they are
// set. json_text() lays a document out — two-space indentation, each list of numbers on one line
// (data columns, not structure), a newline at the end — and leaves the tokens to nlohmann: strings
// with their escapes, integers, booleans and null; doubles are fmt's shortest form that reads back
// as the same double, as in the CSV files.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace bladestab::cli {

using Json = nlohmann::ordered_json;

// The document's text. JSON has no NaN: a non-finite number is a bug upstream (the commands refuse
// non-finite results before output, finite_results.hpp) and throws std::logic_error naming its key,
// rather than printing null.
std::string json_text(const Json& document);

// A number, or a list of numbers, in which NaN stands for "no value" and is written as null.
Json number_or_null(double value);
Json numbers_or_null(const std::vector<double>& values);

}  // namespace bladestab::cli
