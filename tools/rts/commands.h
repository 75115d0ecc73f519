#pragma once
// Subcommand registration. Each register function adds its subcommand to `app` and, when the
// subcommand is chosen on the command line, sets `run` to the code that carries it out.

#include <CLI/App.hpp>
#include <functional>
#include <memory>
#include <string>
#include <utility>

namespace warpath::tools {

using CommandRunner = std::function<int()>;

// Adds subcommand `name` to `parent`. Its options live in a fresh `Options` (returned, to bind
// the options to) and, when the subcommand is chosen, `run` is set to call `body` with them.
template <class Options>
std::pair<CLI::App*, std::shared_ptr<Options>> addSubcommand(CLI::App& parent, CommandRunner& run,
                                                             const std::string& name,
                                                             const std::string& description,
                                                             int (*body)(const Options&)) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = parent.add_subcommand(name, description);
  cmd->callback([&run, options, body] { run = [options, body] { return body(*options); }; });
  return {cmd, options};
}

void registerPathCommand(CLI::App& app, CommandRunner& run);
void registerBenchCommand(CLI::App& app, CommandRunner& run);
// `rts bench random`, `rts bench paper` and `rts bench movement`, added to `bench` by
// registerBenchCommand.
void registerBenchRandomCommand(CLI::App& bench, CommandRunner& run);
void registerBenchPaperCommand(CLI::App& bench, CommandRunner& run);
void registerBenchMovementCommand(CLI::App& bench, CommandRunner& run);
void registerRunCommand(CLI::App& app, CommandRunner& run);
void registerTestCommand(CLI::App& app, CommandRunner& run);
void registerReplayCommand(CLI::App& app, CommandRunner& run);
void registerViewCommand(CLI::App& app, CommandRunner& run);
void registerReportCommand(CLI::App& app, CommandRunner& run);

}  // namespace warpath::tools
