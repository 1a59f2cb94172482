#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"
#include "commands.hpp"

namespace bladestab::cli {

std::map<std::string, Command> register_commands(CLI::App& app) {
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
  run["check"] = register_check(app);
  return run;
}

void check_command_name(const std::map<std::string, Command>& run, const char* name) {
  std::string names;
  for (const auto& [known, unused] : run) names += (names.empty() ? "" : ", ") + known;
  if (name == nullptr) throw InputError(fmt::format("a command is required: {} (see bladestab --help)", names));
  if (name[0] != '-' && run.count(name) == 0) {
    throw InputError(fmt::format("{}: unknown command; known: {}", echoed(name), names));
  }
}

}  // namespace bladestab::cli
