#pragma once
// The nearest of a list of names to a word that is none of them: a typo's likely meaning,
// for the "did you mean" of an unknown case-set key and of an unknown command-line flag.

#include <cstddef>
#include <span>
#include <string_view>

namespace pb {

// Levenshtein distance: insertions, deletions and substitutions of one character.
std::size_t edit_distance(std::string_view a, std::string_view b);

// The name at the least edit distance from word, if it is at most max_edits away (a
// word further from every name is no longer a typo of one); "" otherwise. Ties go to the
// first name in the list.
std::string_view nearest_name(std::string_view word, std::span<const std::string_view> names,
                              std::size_t max_edits = 2);

}  // namespace pb
