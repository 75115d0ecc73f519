// The `rts` program's top level: the app, its subcommands, and exit codes for what escapes them.

#include "rts/rts_main.h"

#include <fmt/core.h>

#include <CLI/CLI.hpp>

#include "rts/cli_support.h"
#include "rts/commands.h"

namespace warpath::tools {

int rtsMain(int argc, char** argv) {
  CLI::App app{
      "warpath: a deterministic RTS simulation whose units plan size- and terrain-aware routes,\n"
      "avoid each other through Box2D and are drawn headlessly; scenarios, replays, benchmarks.\n"
      "Coordinates are X,Y with X the column and Y the row, from the top-left, as in MovingAI."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "warpath 0.1.0");

  CommandRunner run;
  registerPathCommand(app, run);
  registerBenchCommand(app, run);
  registerRunCommand(app, run);
  registerTestCommand(app, run);
  registerReplayCommand(app, run);
  registerViewCommand(app, run);
  registerReportCommand(app, run);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadInput;
  }
  try {
    return run();
  } catch (const BadInput& e) {
    fmt::print(stderr, "rts: error: {}\n", e.message);
    return kExitBadInput;
  }
}

}  // namespace warpath::tools
