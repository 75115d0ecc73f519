#pragma once
// Checks an EnumNames table: every value in `values` has a name, every name parses back to its
// value, names are unique, and list() shows each value once.

#include <gtest/gtest.h>

#include <initializer_list>
#include <set>
#include <string>
#include <string_view>

#include "pathing/enum_names.h"

namespace warpath::testing {

template <class E, std::size_t N>
void expectRoundTrip(const EnumNames<E, N>& table, std::initializer_list<E> values) {
  std::set<std::string_view> names;
  for (E value : values) {
    const std::string_view name = table.name(value);
    EXPECT_NE(name, "?") << "value " << static_cast<int>(value) << " has no name";
    EXPECT_EQ(table.parse(name), value) << name;
    EXPECT_TRUE(names.insert(name).second) << "duplicate name " << name;
  }
  std::set<std::string_view> spellings;
  for (const auto& row : table.rows())
    EXPECT_TRUE(spellings.insert(row.name).second) << "spelling twice in the table: " << row.name;
  std::string expected;
  for (E value : values) {
    if (!expected.empty()) expected += ", ";
    expected += table.name(value);
  }
  EXPECT_EQ(table.list(), expected);
}

}  // namespace warpath::testing
