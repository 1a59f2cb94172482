// bladestab: dynamic stability of rotating blades whose tips rub the casing.
#include <cstdio>
#include <map>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bladestab/input_error.hpp"
#include "commands.hpp"

int main(int argc, char** argv) {
  using namespace bladestab::cli;
  CLI::App app{"bladestab: modes, Campbell diagrams and dynamic stability of rotating Timoshenko blades"};
  app.require_subcommand(1);
  std::map<std::string, Command> run;
  run["modes"] = register_modes(app);
  run["campbell"] = register_campbell(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
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
