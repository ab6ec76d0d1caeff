// The ctx of a lesson (lua/lesson.hpp): ctx:expect by the contract of API.md "Lessons and
// checks" — every case of issue 12 item 15, each with the verdict a teacher would give by
// hand, never rigidlab's own output — ctx:expect_range, the ctx's lifetime (item 1): a ctx
// used after its lesson, after its __gc, or a vec3 dressed in its metatable is an error; and
// ctx:plot (issue 17 item 3): fitted to the lesson's width, checked as plot.lines checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bindings/lua_fixture.hpp"
#include "lua/lesson.hpp"
#include "lua/text_layout.hpp"

namespace {

using rigidlab::lua::LessonContext;

struct Capture : rigidlab::lua::LessonOutput {
  std::string text;
  void write(const std::string& lines) override { text += lines; }
};

class LessonContextTest : public LuaFixture {
 protected:
  void SetUp() override {
    LuaFixture::SetUp();
    context.output = &output;
    context.width = 200;  // one line per check
    rigidlab::lua::push_lesson_context(L, context);
    lua_setglobal(L, "ctx");
  }
  void TearDown() override {
    context.ended = true;
    LuaFixture::TearDown();
  }

  // Runs `call` (a ctx:expect or ctx:expect_range call) and checks its verdict: the returned
  // boolean, the tally, and the line it printed (✓ or ✗, with `reason` on ✗).
  void verdict(const std::string& call, bool ok, const std::string& reason = "") {
    SCOPED_TRACE(call);
    const int passed = context.passed, failed = context.failed;
    output.text.clear();
    ASSERT_EQ(run(("result = " + call).c_str()), "");
    lua_getglobal(L, "result");
    EXPECT_EQ(lua_toboolean(L, -1) != 0, ok) << output.text;
    lua_pop(L, 1);
    EXPECT_EQ(context.passed, passed + (ok ? 1 : 0));
    EXPECT_EQ(context.failed, failed + (ok ? 0 : 1));
    EXPECT_EQ(output.text.rfind(ok ? "  ✓ " : "  ✗ ", 0), 0u) << output.text;
    if (!reason.empty()) {
      EXPECT_NE(output.text.find(reason), std::string::npos)
          << "the line should say '" << reason << "': " << output.text;
    }
  }

  Capture output;
  LessonContext context;
};

TEST_F(LessonContextTest, TablesAreComparedByEveryKey) {
  verdict(R"(ctx:expect("t", {a = 1}, {a = 2}))", false, "(key a: off by 1;");
  verdict(R"(ctx:expect("t", {a = 1}, {a = 1}))", true);
  verdict(R"(ctx:expect("t", {1, x = 5}, {1, x = 7}))", false, "key x: off by 2");
  verdict(R"(ctx:expect("t", {1, x = 5}, {1, x = 5}))", true);
  verdict(R"(ctx:expect("t", {1, 2, 3}, {1, 2}))", false, "key [3]: not expected (got 3)");
  verdict(R"(ctx:expect("t", {1, 2}, {1, 2, 3}))", false, "key [3]: missing (want 3)");
  verdict(R"(ctx:expect("t", {a = 1}, {a = 1, b = false}))", false, "key b: missing (want false)");
  verdict(R"(ctx:expect("t", {}, {}))", true);
  verdict(R"(ctx:expect("t", {1, 2}, {2, 1}))", false, "key [1]: off by 1");
  // the first difference in a fixed order: the list, then the other keys sorted
  verdict(R"(ctx:expect("t", {b = 1, a = 1, 5}, {b = 2, a = 2, 6}))", false, "key [1]:");
  verdict(R"(ctx:expect("t", {b = 1, a = 1}, {b = 2, a = 2}))", false, "key a:");
  verdict(R"(ctx:expect("t", {["a b"] = 1}, {["a b"] = 2}))", false, R"(key ["a b"]:)");
}

TEST_F(LessonContextTest, NestedTablesNameThePath) {
  verdict(R"(ctx:expect("t", {pos = {x = 1, y = 2}}, {pos = {x = 1, y = 3}}))", false,
          "key pos.y: off by 1");
  verdict(R"(ctx:expect("t", {{1, 2}, {3, 4}}, {{1, 2}, {3, 5}}))", false, "key [2][2]: off by 1");
  verdict(R"(ctx:expect("t", {p = vec3(1, 2, 3)}, {p = vec3(1, 2.5, 3)}))", false,
          "key p: component y off by 0.5");
  verdict(R"(ctx:expect("t", {p = vec3(1, 2, 3)}, {p = vec3(1, 2, 3)}))", true);
  verdict(R"(ctx:expect("t", {name = "box"}, {name = "bx"}))", false,
          "key name: strings differ at character 2");
  verdict(R"(ctx:expect("t", {a = {}}, {a = 1}))", false, "key a: got a table, want a number");
}

TEST_F(LessonContextTest, StringsBooleansAndNilAreExact) {
  verdict(R"(ctx:expect("s", "abc", "abc"))", true);
  verdict(R"(ctx:expect("s", "", ""))", true);
  verdict(R"(ctx:expect("s", "abc", "abd"))", false, "strings differ at character 3");
  verdict(R"(ctx:expect("s", "ab", "abc"))", false, "got ends at character 3, want goes on");
  verdict(R"(ctx:expect("s", "abc ", "abc"))", false, "want ends at character 4");
  verdict(R"(ctx:expect("s", "ωx", "ωy"))", false, "strings differ at character 2");
  verdict(R"(ctx:expect("s", "1", 1))", false, "got a string, want a number");
  verdict(R"(ctx:expect("s", "abc", "abc"))", true);
  EXPECT_NE(output.text.find(R"(got "abc", want "abc")"), std::string::npos) << output.text;
  verdict(R"(ctx:expect("b", true, true))", true);
  verdict(R"(ctx:expect("b", false, false))", true);
  verdict(R"(ctx:expect("b", true, false))", false, "got true, want false");
  EXPECT_EQ(output.text, "  ✗ b: got true, want false\n") << "the reason is not the values again";
  verdict(R"(ctx:expect("b", 1, true))", false, "got a number, want a boolean");
  verdict(R"(ctx:expect("n", nil, nil))", true);
  verdict(R"(ctx:expect("n", nil, false))", false, "got nil, want a boolean");
  verdict(R"(ctx:expect("n", 0, nil))", false, "got a number, want nil");
}

TEST_F(LessonContextTest, NumbersInfinitiesAndNan) {
  verdict(R"(ctx:expect("x", math.huge, math.huge))", true);
  verdict(R"(ctx:expect("x", -math.huge, -math.huge))", true);
  verdict(R"(ctx:expect("x", math.huge, -math.huge))", false, "off by inf");
  verdict(R"(ctx:expect("x", 1e308, math.huge))", false, "off by inf");
  verdict(R"(ctx:expect("x", 0/0, 0/0))", false, "got nan: nan equals nothing");
  verdict(R"(ctx:expect("x", 1, 0/0))", false, "want nan");
  verdict(R"(ctx:expect("x", 2, 2.0))", true);
  verdict(R"(ctx:expect("x", -0.0, 0))", true);
  verdict(R"(ctx:expect("x", math.maxinteger, math.maxinteger))", true);
  verdict(R"(ctx:expect("x", 1 + 1e-10, 1))", true);  // within the default 1e-9
  verdict(R"(ctx:expect("x", 1 + 1e-8, 1))", false, "tolerance rel 1e-09");
  verdict(R"(ctx:expect("x", 1e6 + 1e-4, 1e6))", true);  // relative to |want|
  verdict(R"(ctx:expect("x", 1.05, 1, {abs = 0.1}))", true);
  verdict(R"(ctx:expect("x", 1.2, 1, {abs = 0.1}))", false, "off by 0.2");
  verdict(R"(ctx:expect("x", 1.0004, 1, 1e-3))", true);
  verdict(R"(ctx:expect("x", {1, math.huge}, {1, math.huge}))", true);
}

TEST_F(LessonContextTest, MathTypesComponentWise) {
  verdict(R"(ctx:expect("v", vec3(1, 2, 3), vec3(1, 2, 3)))", true);
  verdict(R"(ctx:expect("v", vec3(1, 2, 3), vec3(1, 2, 4)))", false, "component z off by 1");
  verdict(R"(ctx:expect("v", vec3(1, 2, 3), {1, 2, 3}))", false, "got a vec3, want a table");
  verdict(R"(ctx:expect("q", quat(1, 0, 0, 0), quat(0, 1, 0, 0)))", false, "component w off by 1");
  verdict(R"(ctx:expect("m", mat3.identity(), mat3.identity()))", true);
  verdict(R"(ctx:expect("m", mat3.identity(), mat3.diag(1, 1, 2)))", false,
          "entry (3, 3) off by 1");
  verdict(R"(ctx:expect("m", mat3.identity(), vec3(1, 1, 1)))", false, "got a mat3, want a vec3");
}

TEST_F(LessonContextTest, MetamethodsCannotMakeDifferentValuesAgree) {
  verdict(R"(ctx:expect("t", setmetatable({}, {__index = {a = 1}}), {a = 1}))", false,
          "key a: missing (want 1)");
  verdict(R"(ctx:expect("t", setmetatable({a = 1}, {__eq = function() return true end}),
                        setmetatable({a = 2}, {__eq = function() return true end})))",
          false, "key a: off by 1");
  verdict(R"(ctx:expect("t", setmetatable({}, {__len = function() return 3 end}), {}))", true);
  verdict(R"(ctx:expect("t", setmetatable({}, {__pairs = function() error("ran") end}), {a = 1}))",
          false, "key a: missing");
}

TEST_F(LessonContextTest, CyclesAndSharedTables) {
  verdict(R"((function() local a, b = {}, {} a.self, b.self = a, b
            return ctx:expect("t", a, b) end)())",
          true);
  verdict(R"((function() local a, b = {x = 1}, {x = 2} a.self, b.self = a, b
            return ctx:expect("t", a, b) end)())",
          false, "key x: off by 1");
  // 2^40 paths through shared tables: each pair is compared once
  verdict(R"((function() local t, u = {1}, {1}
            for i = 1, 40 do t, u = {t, t}, {u, u} end
            return ctx:expect("t", t, u) end)())",
          true);
  verdict(R"((function() local t, u = {}, {}
            for i = 1, 100 do t, u = {t}, {u} end
            return ctx:expect("t", t, u) end)())",
          false, "nested deeper than 64 levels");
}

TEST_F(LessonContextTest, OtherValuesOnlyEqualThemselves) {
  verdict(R"(ctx:expect("f", print, print))", true);
  verdict(R"(ctx:expect("f", print, error))", false, "got another function");
  verdict(R"((function() local b = body{mass = 1, inertia = mat3.identity()}
            return ctx:expect("b", b, b) end)())",
          true);
  verdict(R"(ctx:expect("b", body{mass = 1, inertia = mat3.identity()},
                        body{mass = 1, inertia = mat3.identity()}))",
          false, "got another body");
}

TEST_F(LessonContextTest, TheFailureIsRecordedWithItsReason) {
  verdict(R"(ctx:expect("t", {a = 1}, {a = 2}))", false);
  ASSERT_EQ(context.failures.size(), 1u);
  EXPECT_EQ(context.failures[0],
            "t: got {a = 1}, want {a = 2} (key a: off by 1; tolerance rel 1e-09)");
}

TEST_F(LessonContextTest, ToleranceWithAReasonIsPrinted) {
  verdict(R"(ctx:expect("g", 9.81, 9.8, {rel = 0.01, reason = "the document rounds g"}))", true,
          "(tolerance rel 0.01: the document rounds g)");
  context.tolerance = {0.0, 1e-3, "the document gives 4 digits"};
  verdict(R"(ctx:expect("x", 1.0004, 1))", true);  // the lesson's default: its heading says why
  EXPECT_EQ(output.text, "  ✓ x: got 1.0004, want 1\n");
  verdict(R"(ctx:expect("x", 1.01, 1))", false, "(off by 0.01; tolerance rel 0.001)\n");
  verdict(R"(ctx:expect("s", "a", "b"))", false, "(strings differ at character 1)\n");
  EXPECT_EQ(run(R"(ctx:expect("x", 1, 1, {rel = 1, why = "x"}))"),
            "test:1: bad argument #4 to 'ctx:expect' (unknown field 'why' (fields are: abs, rel, "
            "reason))");
  EXPECT_EQ(run(R"(ctx:expect("x", 1, 1, {rel = -1}))"),
            "test:1: bad argument #4 to 'ctx:expect' (field 'rel' must be a finite number >= 0, "
            "got -1)");
}

TEST_F(LessonContextTest, ExpectRange) {
  verdict(R"(ctx:expect_range("h", 3.2, 3, 3.5))", true, "got 3.2, want in [3, 3.5]");
  verdict(R"(ctx:expect_range("h", 3, 3, 3.5))", true);
  verdict(R"(ctx:expect_range("h", 2.5, 3, 3.5))", false, "below the low bound by 0.5");
  verdict(R"(ctx:expect_range("h", 4, 3, 3.5))", false, "above the high bound by 0.5");
  verdict(R"(ctx:expect_range("h", 4, 3, nil))", true, "want ≥ 3");
  verdict(R"(ctx:expect_range("h", 4, nil, 3))", false, "want ≤ 3");
  verdict(R"(ctx:expect_range("h", math.huge, 0, nil))", true);
  verdict(R"(ctx:expect_range("h", 0/0, 0, 1))", false, "got nan: nan is in no range");
  verdict(R"(ctx:expect_range("h", "2", 0, 3))", false, "got a string, want a number");
  verdict(R"(ctx:expect_range("h", nil, 0, 3))", false, "got nil, want a number");
  EXPECT_EQ(run(R"(ctx:expect_range("h", 1))"),
            "test:1: bad argument #3 to 'ctx:expect_range' (a bound expected: low and high are "
            "both nil)");
  EXPECT_EQ(run(R"(ctx:expect_range("h", 1, 2, 1))"),
            "test:1: bad argument #4 to 'ctx:expect_range' (high must be >= low, got low 2 and "
            "high 1)");
  EXPECT_EQ(run(R"(ctx:expect_range("h", 1, 0/0, 1))"),
            "test:1: bad argument #3 to 'ctx:expect_range' (a bound must be a number, got nan)");
  EXPECT_EQ(run(R"(ctx:expect_range("h", 1, "0", 1))"),
            "test:1: bad argument #3 to 'ctx:expect_range' (number or nil expected, got string)");
}

TEST_F(LessonContextTest, AnEndedLessonsCtxIsAnError) {
  ASSERT_EQ(run(R"(ctx:expect("x", 1, 1))"), "");
  context.ended = true;
  EXPECT_EQ(run(R"(ctx:expect("x", 1, 2))"),
            "test:1: calling 'ctx:expect' on bad self (the lesson has ended: its ctx can no "
            "longer show or check anything)");
  EXPECT_EQ(context.passed, 1);
  EXPECT_EQ(context.failed, 0);
}

TEST_F(LessonContextTest, AFinalisedCtxIsAnErrorAndItsGcCanRunTwice) {
  ASSERT_EQ(run(R"(
    local gc = debug.getmetatable(ctx).__gc
    gc(ctx)
    gc(ctx)
  )"),
            "");
  EXPECT_EQ(run(R"(ctx:expect("x", 1, 2))"),
            "test:1: calling 'ctx:expect' on bad self (the lesson context was garbage-collected "
            "(it is used from a finaliser))");
  EXPECT_EQ(run(R"(ctx:say("x"))"),
            "test:1: calling 'ctx:say' on bad self (the lesson context was garbage-collected "
            "(it is used from a finaliser))");
  EXPECT_EQ(run("assert(tostring(ctx) == 'lesson context (garbage-collected)')"), "");
  EXPECT_EQ(context.failed, 0);
}

TEST_F(LessonContextTest, AVec3InTheCtxMetatableIsNoCtx) {
  EXPECT_EQ(run(R"(
    local mt = debug.getmetatable(ctx)
    local v = vec3(1, 2, 3)
    debug.setmetatable(v, mt)
    mt.__gc(v)
    mt.__gc(v)
    v:expect("x", 1, 1)
  )"),
            "test:7: calling 'ctx:expect' on bad self (lesson context expected, got vec3)");
  EXPECT_EQ(run(R"(
    local mt = debug.getmetatable(ctx)
    local f = io.tmpfile()
    debug.setmetatable(f, mt)
    mt.__gc(f)
    return f:show("x", 1)
  )"),
            "test:6: calling 'ctx:show' on bad self (lesson context expected, got userdata)");
  EXPECT_EQ(run(R"(ctx:expect("still a ctx", 1, 1))"), "");
  EXPECT_EQ(context.passed, 1);
}

TEST_F(LessonContextTest, ValuesAreWrittenWithTheirKeys) {
  ASSERT_EQ(run(R"(ctx:show("t", {1, 2, x = 5, name = "a", [10] = true, sub = {vec3(1, 2, 3)}}))"),
            "");
  EXPECT_EQ(output.text, "  t = {1, 2, [10] = true, name = \"a\", sub = {(1, 2, 3)}, x = 5}\n");
}

}  // namespace

namespace {

// The widest line of `text` in code points.
size_t widest_line(const std::string& text) {
  size_t widest = 0, start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    widest = std::max(widest, rigidlab::lua::display_width(text.substr(start, end - start)));
    start = end + 1;
  }
  return widest;
}

const char* const sine_plot = R"lua(
  local t, y = {}, {}
  for i = 0, 60 do t[#t + 1], y[#y + 1] = i / 10, math.sin(i / 10) end
  ctx:plot{{x = t, y = y, label = "sin t"}, title = "A sine", xlabel = "t (s)", ylabel = "y",
           height = 8}
)lua";

TEST_F(LessonContextTest, APlotFitsTheLessonsWidth) {
  for (int columns : {40, 60, 80, 100}) {
    SCOPED_TRACE(columns);
    context.width = columns;
    output.text.clear();
    ASSERT_EQ(run(sine_plot), "");
    EXPECT_EQ(widest_line(output.text), static_cast<size_t>(columns)) << output.text;
    EXPECT_NE(output.text.find("\n    "), std::string::npos) << "indented like a table";
    EXPECT_NE(output.text.find("A sine"), std::string::npos);
    EXPECT_NE(output.text.find("sin t"), std::string::npos);
  }
}

TEST_F(LessonContextTest, APlotKeepsTheWidthItAskedFor) {
  context.width = 100;
  ASSERT_EQ(run("ctx:plot{{y = {1, 2, 3}}, width = 20, height = 5}"), "");
  EXPECT_LT(widest_line(output.text), 40u) << output.text;
}

TEST_F(LessonContextTest, APlotIsCheckedLikePlotLinesEvenWhenNothingIsShown) {
  context.output = nullptr;  // check mode
  EXPECT_EQ(run("ctx:plot{{y = {1, 0/0}}}"),
            "test:1: bad argument #1 to 'ctx:plot' (series 1: y[2] is nan)");
  EXPECT_EQ(run("ctx:plot{}"),
            "test:1: bad argument #1 to 'ctx:plot' (at least one series {x = {...}, y = {...}} "
            "expected)");
  EXPECT_NE(run("ctx:plot({{y = {1}}}, 2)").find("bad argument #2 to 'ctx:plot'"),
            std::string::npos);
}

// A page that records the charts it is given instead of drawing them.
struct ChartCapture : rigidlab::lua::LessonOutput {
  std::vector<rigidlab::present::Chart> charts;
  std::vector<rigidlab::lua::PlotSize> sizes;
  void write(const std::string&) override {}
  void plot(const rigidlab::present::Chart& chart, const rigidlab::lua::PlotSize& size) override {
    charts.push_back(chart);
    sizes.push_back(size);
  }
};

TEST_F(LessonContextTest, APlotReachesThePageAsAChart) {
  ChartCapture page;
  context.output = &page;
  context.width = 72;
  ASSERT_EQ(run(sine_plot), "");
  ASSERT_EQ(page.charts.size(), 1u);
  EXPECT_EQ(page.charts[0].title, "A sine");
  ASSERT_EQ(page.charts[0].series.size(), 1u);
  EXPECT_EQ(page.charts[0].series[0].x.size(), 61u);
  EXPECT_DOUBLE_EQ(page.charts[0].series[0].y[10], std::sin(1.0));
  EXPECT_EQ(page.sizes[0].width, 0) << "no width asked: fit";
  EXPECT_EQ(page.sizes[0].height, 8);
  EXPECT_EQ(page.sizes[0].columns, 72);
}

}  // namespace
