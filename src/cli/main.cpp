// bladestab: dynamic stability of rotating blades whose tips rub the casing.
#include <cstdio>
#include <map>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bladestab/blas_threads.hpp"
#include "bladestab/input_error.hpp"
#include "commands.hpp"

namespace {

std::string command_names(const std::map<std::string, bladestab::cli::Command>& run) {
  std::string names;
  for (const auto& [name, unused] : run) names += (names.empty() ? "" : ", ") + name;
  return names;
}

// "Could not convert: --count = abc" → what --count accepts, from its type name.
std::string expected_type(const CLI::App& app, const std::string& message) {
  const auto start = message.find("--");
  const auto end = message.find(' ', start);
  if (start == std::string::npos) return "a value of the option's type is expected";
  const std::string name = message.substr(start, end - start);
  for (const CLI::App* command : app.get_subcommands()) {
    for (const CLI::Option* option : command->get_options()) {
      if (!option->check_lname(name.substr(2))) continue;
      const std::string type = option->get_type_name();
      if (type.find("INT") != std::string::npos) return "must be an integer (comma-separated integers for a list)";
      if (type.find("FLOAT") != std::string::npos) return "must be a number";
      return "must be " + type;
    }
  }
  return "a value of the option's type is expected";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace bladestab::cli;
  bladestab::use_single_threaded_blas();
  CLI::App app{"bladestab: modes, Campbell diagrams and dynamic stability of rotating Timoshenko blades"};
  app.require_subcommand(1);
  std::map<std::string, Command> run;
  run["modes"] = register_modes(app);
  run["campbell"] = register_campbell(app);
  run["stability"] = register_stability(app);
  run["boundaries"] = register_boundaries(app);
  run["map"] = register_map(app);
  run["transient"] = register_transient(app);
  run["crosscheck"] = register_crosscheck(app);
  run["sweep"] = register_sweep(app);
  if (argc < 2) {
    fmt::print(stderr, "bladestab: error: a command is required: {} (see bladestab --help)\n", command_names(run));
    return 2;
  }
  if (argv[1][0] != '-' && run.count(argv[1]) == 0) {
    fmt::print(stderr, "bladestab: error: {}: unknown command; known: {}\n", argv[1], command_names(run));
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ConversionError& e) {
    fmt::print(stderr, "bladestab: error: {}: {}\n", e.what(), expected_type(app, e.what()));
    return 2;
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "bladestab: error: {} (see bladestab --help)\n", e.what());
    return 2;
  }
  try {
    run.at(app.get_subcommands().front()->get_name())();
  } catch (const bladestab::InputError& e) {
    fmt::print(stderr, "bladestab: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "bladestab: failed: {}\n", e.what());
    return 1;
  }
  return 0;
}
