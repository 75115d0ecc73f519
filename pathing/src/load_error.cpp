#include "pathing/load_error.h"

namespace warpath::pathing {

std::string LoadError::describe() const {
  // Compiler-style "file:line: message" so editors and terminals can jump to the spot.
  // Appends rather than chains operator+, which trips a false -Wrestrict in GCC 12 at -O3.
  std::string out = file;
  if (line > 0) {
    out.append(out.empty() ? "line " : ":");
    out.append(std::to_string(line));
  }
  if (!out.empty()) out.append(": ");
  out.append(message);
  return out;
}

}  // namespace warpath::pathing
