#pragma once
// Subcommand registration. Each register function adds its subcommand to `app` and, when the
// subcommand is chosen on the command line, sets `run` to the code that carries it out.

#include <CLI/App.hpp>
#include <functional>

namespace warpath::tools {

using CommandRunner = std::function<int()>;

void registerPathCommand(CLI::App& app, CommandRunner& run);
void registerBenchCommand(CLI::App& app, CommandRunner& run);

}  // namespace warpath::tools
