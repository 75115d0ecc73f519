#pragma once
// Shared pieces of the `rts` subcommands: exit codes, argument parsing, loading inputs.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "pathing/grid_map.h"

namespace warpath::tools {

// Process exit codes every subcommand uses.
enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,    // ran, but the outcome is negative (no path, a check failed)
  kExitBadInput = 2,  // bad command line, unreadable or malformed file
};

// Thrown by subcommands for bad input; main prints it as "rts: error: ..." and exits 2.
struct BadInput {
  std::string message;
};

// A whole decimal number filling all of `text`, else nullopt.
std::optional<int> parseInt(std::string_view text);

// A CLI11 check that an option's value is a whole number in [lo, hi], with a readable message
// ("--until: must be a whole number between 0 and 1000000000, got '-1'") instead of CLI11's
// range in 300 digits. Refuses numbers too large for any integer type too.
CLI::Validator wholeNumberIn(std::int64_t lo, std::int64_t hi);

// The same for a number in (0, hi]: "--speed: must be a number greater than 0 and at most
// 1000000, got '0'".
CLI::Validator positiveNumberUpTo(double hi);

// "X,Y" with integers; throws BadInput naming `option` otherwise.
pathing::Cell parseCell(std::string_view text, std::string_view option);

// Creates an output file's folder before a run, so that a bad path fails at once (exit 2)
// instead of after a long simulation; throws BadInput naming `option`. Nothing for "".
void prepareOutputPath(const std::string& file, const std::string& option);

// Loads a MovingAI map or throws BadInput with file, line and problem.
pathing::GridMap loadMapOrThrow(const std::string& file);

}  // namespace warpath::tools
