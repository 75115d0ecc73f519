#pragma once
// The `rts` program's whole work, in the CLI library: main() only calls it, so the executable's
// own source includes nothing heavy (CLI11 compiled once more in it cost 15 s a build).

namespace warpath::tools {

// Parses the command line, runs the chosen subcommand and returns the process's exit code.
int rtsMain(int argc, char** argv);

}  // namespace warpath::tools
