#pragma once
// One table per enum gives its names, its parser and the list that error messages show, so
// the three can never disagree. A value may have several spellings: the first row that names
// it is its canonical name, later rows are aliases accepted by parse() and left out of list().
//
//   inline constexpr EnumNames<Colour, 3> kColourNames{{{
//       {Colour::Red, "red"}, {Colour::Green, "green"}, {Colour::Green, "verdant"}}}};
//   kColourNames.name(Colour::Green)  -> "green"
//   kColourNames.parse("verdant")     -> Colour::Green
//   kColourNames.list()               -> "red, green"
//   kColourNames.list(", ", " or ")   -> "red or green"

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace warpath {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

template <class E, std::size_t N>
class EnumNames {
 public:
  constexpr explicit EnumNames(std::array<EnumName<E>, N> rows) : rows_(rows) {}

  // The canonical name, or "?" for a value the table does not have.
  constexpr std::string_view name(E value) const {
    for (const EnumName<E>& row : rows_)
      if (row.value == value) return row.name;
    return "?";
  }
  // Exact match against every spelling (canonical names and aliases).
  constexpr std::optional<E> parse(std::string_view text) const {
    for (const EnumName<E>& row : rows_)
      if (row.name == text) return row.value;
    return std::nullopt;
  }
  // The canonical names in table order, for "expected one of: …" messages; `last` goes before
  // the last name instead of `separator` ("a, b or c").
  std::string list(std::string_view separator = ", ") const { return list(separator, separator); }
  std::string list(std::string_view separator, std::string_view last) const {
    std::size_t names = 0;
    for (std::size_t i = 0; i < N; ++i)
      names += isCanonical(i) ? 1 : 0;
    std::string out;
    std::size_t written = 0;
    for (std::size_t i = 0; i < N; ++i) {
      if (!isCanonical(i)) continue;
      if (written > 0) out.append(written + 1 == names ? last : separator);
      out.append(rows_[i].name);
      ++written;
    }
    return out;
  }
  constexpr const std::array<EnumName<E>, N>& rows() const { return rows_; }

 private:
  constexpr bool isCanonical(std::size_t i) const {
    for (std::size_t j = 0; j < i; ++j)
      if (rows_[j].value == rows_[i].value) return false;
    return true;
  }
  std::array<EnumName<E>, N> rows_;
};

}  // namespace warpath
