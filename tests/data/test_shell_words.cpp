// Command lines as run-info.csv records them: quoted word by word, read back word by word, and the unquoted lines
// of datasets recorded before quoting still read at their spaces.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "rollsense/shell_words.hpp"

using rollsense::shell_join;
using rollsense::shell_quote;
using rollsense::shell_split;

TEST_CASE("a word is quoted only when a shell would split or expand it", "[data][shell]") {
    CHECK(shell_quote("runs=2") == "runs=2");
    CHECK(shell_quote("/tmp/a-b_c.lua") == "/tmp/a-b_c.lua");
    CHECK(shell_quote("my run") == "'my run'");
    CHECK(shell_quote("") == "''");
    CHECK(shell_quote("it's") == "'it'\\''s'");
    CHECK(shell_quote("$HOME") == "'$HOME'");
}

TEST_CASE("joined words split back into the same words", "[data][shell]") {
    const std::vector<std::string> words = {"rollsense", "run", "my exp.lua", "--set", "objects=C1, C2", "",
                                            "it's", "a\"b", "back\\slash", "tab\there"};
    CHECK(shell_split(shell_join(words)) == words);
}

TEST_CASE("a command line recorded unquoted splits at its spaces, and double quotes read as a shell reads them",
          "[data][shell]") {
    CHECK(shell_split("rollsense run s.lua  --seed 11 -q") ==
          std::vector<std::string>{"rollsense", "run", "s.lua", "--seed", "11", "-q"});
    CHECK(shell_split(R"(run "a b" "x\"y" c\ d)") == std::vector<std::string>{"run", "a b", "x\"y", "c d"});
    CHECK(shell_split("").empty());
}
