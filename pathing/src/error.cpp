#include "pathing/error.h"

namespace warpath {

std::string Error::describe() const {
  // Appends rather than chains operator+, which trips a false -Wrestrict in GCC 12 at -O3.
  std::string out = file;
  if (line > 0) {
    out.append(out.empty() ? "line " : ":");
    out.append(std::to_string(line));
    if (column > 0) {
      out.append(":");
      out.append(std::to_string(column));
    }
  }
  if (!out.empty()) out.append(": ");
  out.append(message);
  return out;
}

}  // namespace warpath
