// Tests for present/terminal.cpp's key decoding: the byte sequences xterm and tmux send (ECMA-48
// CSI and SS3 cursor keys, xterm's ";2" shift parameter), sequences split across reads, and
// bytes of no key. (The session itself is tested in a real terminal: tests/cli/view_test.sh.)
#include "present/terminal.hpp"

#include <gtest/gtest.h>

namespace rigidlab::present {
namespace {

std::vector<Key> decode(std::string bytes) { return decode_keys(bytes); }

TEST(Keys, PlainKeysAndArrows) {
  EXPECT_EQ(decode(" q+-o"), (std::vector<Key>{Key::pause, Key::quit, Key::faster, Key::slower,
                                              Key::overlays}));
  EXPECT_EQ(decode("\x1b[C\x1b[D\x1bOC\x1bOD"),
            (std::vector<Key>{Key::step_forward, Key::step_back, Key::step_forward, Key::step_back}));
  EXPECT_EQ(decode("\x1b[1;2C\x1b[1;2D\x1b[1;2A\x1b[1;2B"),
            (std::vector<Key>{Key::orbit_right, Key::orbit_left, Key::orbit_up, Key::orbit_down}));
  EXPECT_EQ(decode("\x1b[A\x1b[B"), (std::vector<Key>{Key::orbit_up, Key::orbit_down}));
  EXPECT_EQ(decode("adws"), (std::vector<Key>{Key::orbit_left, Key::orbit_right, Key::orbit_up,
                                              Key::orbit_down}));
}

TEST(Keys, OtherBytesAndSequencesAreDropped) {
  EXPECT_EQ(decode("xyz\x01\x1b[5~\x1b[1;5C\x1b[200~"), std::vector<Key>{});  // PgUp, Ctrl+→, paste
  EXPECT_EQ(decode("\x1bq"), std::vector<Key>{Key::quit});  // Escape then q
}

TEST(Keys, ASequenceCutShortWaitsForTheRest) {
  std::string input = "q\x1b[1;";
  EXPECT_EQ(decode_keys(input), std::vector<Key>{Key::quit});
  EXPECT_EQ(input, "\x1b[1;");
  input += "2C";
  EXPECT_EQ(decode_keys(input), std::vector<Key>{Key::orbit_right});
  EXPECT_EQ(input, "");
  input = "\x1b";
  EXPECT_EQ(decode_keys(input), std::vector<Key>{});
  EXPECT_EQ(input, "\x1b");
}

}  // namespace
}  // namespace rigidlab::present
