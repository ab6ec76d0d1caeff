// Tests for present/history.hpp, the view's ring of saved states: against a plain model (a
// list with a cursor whose future is cut by a new state and whose oldest state falls off past
// the capacity), over a long pseudo-random run of every operation; and the slots allocated
// once: saving a state of the prototype's size into a slot reuses that slot's memory.
#include "present/history.hpp"

#include <gtest/gtest.h>

#include <deque>
#include <set>
#include <vector>

namespace rigidlab::present {
namespace {

// The model: what the user expects of undo and redo.
struct Model {
  std::size_t capacity;
  std::deque<int> states;
  std::size_t cursor = 0;
  void record(int s) {
    if (!states.empty()) states.erase(states.begin() + static_cast<long>(cursor) + 1, states.end());
    states.push_back(s);
    if (states.size() > capacity) states.pop_front();
    cursor = states.size() - 1;
  }
};

TEST(History, MatchesAListWithACursorOverALongRun) {
  for (const std::size_t capacity : {1u, 2u, 7u, 40u}) {
    History<int> h(capacity, -1);
    Model m{capacity};
    unsigned seed = 12345;
    int next_state = 0;
    for (int op = 0; op < 3000; ++op) {
      seed = seed * 1103515245u + 12345u;
      const unsigned what = (seed >> 16) % 4;
      if (what == 0 || h.empty()) {
        h.record() = next_state;
        m.record(next_state++);
      } else if (what == 1) {
        const bool moved = h.back();
        EXPECT_EQ(moved, m.cursor > 0);
        if (moved) --m.cursor;
      } else if (what == 2) {
        const int* after = h.next();
        ASSERT_EQ(after != nullptr, m.cursor + 1 < m.states.size());
        if (after != nullptr) EXPECT_EQ(*after, m.states[m.cursor + 1]);
        const bool moved = h.forward();
        EXPECT_EQ(moved, after != nullptr);
        if (moved) ++m.cursor;
      } else if (seed % 97 == 0) {
        h.clear();
        m.states.clear();
        m.cursor = 0;
      } else if (seed % 89 == 0 && m.capacity > 1) {  // fewer slots: the oldest states go
        h.shrink(--m.capacity);
        const std::size_t dropped = m.states.size() > m.capacity ? m.states.size() - m.capacity : 0;
        m.states.erase(m.states.begin(), m.states.begin() + static_cast<long>(dropped));
        m.cursor = m.cursor >= dropped ? m.cursor - dropped : 0;
      }
      ASSERT_EQ(h.capacity(), m.capacity);
      ASSERT_EQ(h.size(), m.states.size()) << "op " << op;
      ASSERT_EQ(h.position(), m.cursor) << "op " << op;
      EXPECT_EQ(h.at_newest(), m.states.empty() || m.cursor + 1 == m.states.size());
      for (std::size_t k = 0; k < m.states.size(); ++k) ASSERT_EQ(h.at(k), m.states[k]);
      if (!m.states.empty()) EXPECT_EQ(h.current(), m.states[m.cursor]);
    }
  }
}

TEST(History, RecordingCutsTheFutureSeenBeforeARewind) {
  History<int> h(10, 0);
  for (int s = 1; s <= 5; ++s) h.record() = s;
  EXPECT_TRUE(h.back());
  EXPECT_TRUE(h.back());
  EXPECT_EQ(h.current(), 3);
  EXPECT_EQ(*h.next(), 4);
  h.record() = 40;  // a different step from 3: 4 and 5 are gone
  EXPECT_EQ(h.size(), 4u);
  EXPECT_TRUE(h.at_newest());
  EXPECT_EQ(h.at(3), 40);
  EXPECT_EQ(h.next(), nullptr);
}

TEST(History, SlotsAreAllocatedOnceAndReused) {
  const std::vector<double> prototype(100, 0.0);
  History<std::vector<double>> h(4, prototype);
  std::set<const double*> blocks;
  for (std::size_t k = 0; k < 4; ++k) blocks.insert(h.record().data());
  EXPECT_EQ(blocks.size(), 4u);
  for (int round = 0; round < 20; ++round) {
    const std::vector<double> state(100, round);
    std::vector<double>& slot = h.record();
    slot = state;  // a copy of the same size (as World::save_state's): reuses the slot's block
    EXPECT_EQ(blocks.count(slot.data()), 1u) << "round " << round;
  }
  EXPECT_EQ(h.size(), 4u);
  EXPECT_EQ(h.at(0)[0], 16.0);
}

TEST(History, ShrinkingKeepsTheNewestAndTheCursorOnItsState) {
  History<int> h(6, 0);
  for (int s = 1; s <= 6; ++s) h.record() = s;  // 1..6, full
  h.record() = 7;                               // 2..7, the ring wrapped
  h.back();
  h.back();                                     // on 5
  h.shrink(4);                                  // 4..7
  EXPECT_EQ(h.capacity(), 4u);
  EXPECT_EQ(h.size(), 4u);
  EXPECT_EQ(h.at(0), 4);
  EXPECT_EQ(h.current(), 5);
  h.shrink(1);                                  // 7; the cursor's state is gone: the oldest kept
  EXPECT_EQ(h.current(), 7);
  h.record() = 8;
  EXPECT_EQ(h.size(), 1u);
  EXPECT_EQ(h.at(0), 8);
}

TEST(History, RefusesZeroSlots) {
  EXPECT_THROW(History<int>(0, 0), std::invalid_argument);
  History<int> h(2, 0);
  EXPECT_THROW(h.shrink(0), std::invalid_argument);
}

}  // namespace
}  // namespace rigidlab::present
