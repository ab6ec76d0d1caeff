// The sandbox removes every way to touch the file system, run native or binary code, or
// reach the debug library, and keeps the harmless parts.
#include "lua/sandbox.hpp"

#include <string>

#include "lua_fixture.hpp"

namespace {

class Sandbox : public LuaFixture {
 protected:
  void SetUp() override {
    LuaFixture::SetUp();
    rigidlab::lua::apply_sandbox(L);
  }
};

TEST_F(Sandbox, RemovesFileSystemAndNativeCode) {
  EXPECT_EQ(run("assert(io == nil and package == nil and require == nil)"), "");
  EXPECT_EQ(run("assert(dofile == nil and loadfile == nil)"), "");
  EXPECT_EQ(run("assert(os.execute == nil and os.remove == nil and os.exit == nil)"), "");
  EXPECT_EQ(run("assert(os.getenv == nil and os.rename == nil and os.tmpname == nil)"), "");
  EXPECT_EQ(run("assert(string.dump == nil and ('').dump == nil)"), "");
  EXPECT_EQ(run("assert(debug.getregistry == nil and debug.sethook == nil)"), "");
}

TEST_F(Sandbox, KeepsClockTimeDateTracebackAndRigidlab) {
  EXPECT_EQ(run("assert(type(os.clock()) == 'number' and type(os.time()) == 'number')"), "");
  EXPECT_EQ(run("assert(os.date('%Y') and os.difftime(2, 1) == 1)"), "");
  EXPECT_EQ(run("assert(debug.traceback('x'):find('x'))"), "");
  EXPECT_EQ(run("assert(vec3(1, 2, 3):cross(vec3(4, 5, 6)) == vec3(-3, 6, -3))"), "");
}

TEST_F(Sandbox, LoadAcceptsTextOnly) {
  EXPECT_EQ(run("assert(load('return 1 + 1')() == 2)"), "");
  EXPECT_EQ(run("assert(load('return x', 'chunk', 't', {x = 5})() == 5)"), "");
  // A binary chunk (starting with ESC "Lua") is refused even when the mode allows text only.
  EXPECT_EQ(run("local f, e = load('\\27Lua junk'); assert(f == nil and e:find('binary'))"), "");
  EXPECT_NE(run("load('return 1', 'c', 'b')").find("rigidlab loads text only"), std::string::npos);
}

TEST_F(Sandbox, FileWritersRefuse) {
  EXPECT_NE(run("csv.write('/tmp/x.csv', {x = {1}}, {'x'})")
                .find("bad argument #1 to 'csv.write' (files cannot be written in the sandbox)"),
            std::string::npos);
  EXPECT_NE(run("plot.lines{{y = {1, 2}}, svg = '/tmp/x.svg'}")
                .find("svg files cannot be written in the sandbox"),
            std::string::npos);
  EXPECT_TRUE(rigidlab::lua::is_sandboxed(L));
}

}  // namespace
