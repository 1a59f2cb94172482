#pragma once
// The subcommands. Each registers its options on the app and returns the function that runs it.
#include <functional>
#include <map>
#include <string>

#include <CLI/CLI.hpp>

namespace bladestab::cli {

using Command = std::function<void()>;

// Thrown by a command whose answer is printed and complete but negative: exit status 1, with no
// error line (`check`: a requirement not met) or with `reason` as the "failed" line
// (`boundaries`: none converged).
struct AnswerIsNegative {
  std::string reason;
};

Command register_modes(CLI::App& app);
Command register_campbell(CLI::App& app);
Command register_stability(CLI::App& app);
Command register_boundaries(CLI::App& app);
Command register_map(CLI::App& app);
Command register_transient(CLI::App& app);
Command register_crosscheck(CLI::App& app);
Command register_sweep(CLI::App& app);
Command register_check(CLI::App& app);

// Every subcommand on `app` (one of them required), by name.
std::map<std::string, Command> register_commands(CLI::App& app);

// InputError unless `name` (the first argument; null: none) is a command of `run` or an option
// ("--help"): "a command is required: …" for none, "…: unknown command; known: …" otherwise.
void check_command_name(const std::map<std::string, Command>& run, const char* name);

}  // namespace bladestab::cli
