#pragma once
// Where each operation of a script starts in its text, for errors and reports that name the
// line: a SAX pass over a document already parsed (so it never meets invalid JSON).

#include <cstddef>
#include <string_view>
#include <vector>

namespace sandtin {

/// The 1-based line on which each operation object starts, in order: the elements of a bare
/// top-level array, or of the array under the top-level key "operations".
std::vector<std::size_t> operation_start_lines(std::string_view text);

}  // namespace sandtin
