// cli/chunk_scanner: "open" must mean that Lua's own parser cannot accept the chunk yet — it is
// checked against luaL_loadbuffer on every prefix (by lines) of every Lua file in the source
// tree — and the constructs that made the REPL quadratic must be seen as open.
#include <gtest/gtest.h>

#include <lua.hpp>

#include <dirent.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/chunk_scanner.hpp"

namespace {

using rigidlab::cli::ChunkScanner;

bool open_after(const std::vector<std::string>& lines) {
  ChunkScanner scanner;
  for (const std::string& line : lines) scanner.feed(line);
  return scanner.open();
}

bool open_after(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  if (!text.empty() && text.back() == '\n') lines.emplace_back();
  return open_after(lines);
}

// Whether Lua compiles the text (as the REPL tries it: as is, and as `return text;`).
bool lua_accepts(lua_State* L, const std::string& text) {
  for (const std::string& code : {text, "return " + text + ";"}) {
    const int status = luaL_loadbufferx(L, code.data(), code.size(), "=t", "t");
    lua_pop(L, 1);
    if (status == LUA_OK) return true;
  }
  return false;
}

std::vector<std::string> lua_files(const std::string& directory) {
  std::vector<std::string> files;
  if (DIR* dir = opendir(directory.c_str())) {
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".lua") == 0)
        files.push_back(directory + "/" + name);
    }
    closedir(dir);
  }
  return files;
}

TEST(ChunkScanner, NeverOpenWhereLuaAcceptsAPrefixOfTheSourceTree) {
  lua_State* L = luaL_newstate();
  int prefixes = 0;
  for (const char* folder : {"lessons", "tests/lua", "tests/fuzz/corpus", "tests/lessons"}) {
    for (const std::string& file : lua_files(std::string(RIGIDLAB_SOURCE_DIR) + "/" + folder)) {
      std::ifstream in(file);
      std::vector<std::string> lines;
      std::string text;
      ChunkScanner scanner;
      for (std::string line; std::getline(in, line);) {
        scanner.feed(line);
        text += (lines.empty() ? "" : "\n") + line;
        lines.push_back(line);
        // Every prefix of the first 200 lines, every 10th after (the test stays quick).
        if (lines.size() > 200 && lines.size() % 10 != 0) continue;
        ++prefixes;
        if (scanner.open()) {
          EXPECT_FALSE(lua_accepts(L, text)) << file << ", the first " << lines.size() << " lines";
        }
      }
    }
  }
  EXPECT_GT(prefixes, 1000);  // the tree was found
  lua_close(L);
}

TEST(ChunkScanner, LongCommentsAndStringsAreOpenUntilTheirBracketCloses) {
  EXPECT_TRUE(open_after("--[[\nx\ny"));
  EXPECT_FALSE(open_after("--[[\nx\n]]"));
  EXPECT_TRUE(open_after("--[==[\n]]\n]=]"));  // only the same level closes it
  EXPECT_FALSE(open_after("--[==[\n]]\n]==]"));
  EXPECT_FALSE(open_after("-- [[ a line comment"));
  EXPECT_TRUE(open_after("s = [[\nabc"));
  EXPECT_FALSE(open_after("s = [[\nabc]]"));
  EXPECT_TRUE(open_after("s = [=[ ]] \n"));
  EXPECT_FALSE(open_after("s = '--[['"));  // inside a string: no comment
  EXPECT_FALSE(open_after("s = \"]]\" -- [[x"));
}

TEST(ChunkScanner, StringsOpenOnlyWhenContinued) {
  EXPECT_TRUE(open_after("s = \"abc\\"));       // `\` and a newline
  EXPECT_FALSE(open_after("s = \"abc\\\ndef\""));
  EXPECT_TRUE(open_after("s = 'a\\z"));         // \z skips the line break
  EXPECT_FALSE(open_after("s = 'a\\z\n   b'"));
  EXPECT_FALSE(open_after("s = 'abc"));         // unfinished: Lua's error, not <eof>
  EXPECT_FALSE(open_after("s = 'it\\'s'"));
  EXPECT_FALSE(open_after("s = \"\\\\\""));     // an escaped backslash ends nothing
}

TEST(ChunkScanner, BlocksBracketsAndOperators) {
  EXPECT_TRUE(open_after("function f()"));
  EXPECT_FALSE(open_after("function f() end"));
  EXPECT_TRUE(open_after("for i = 1, 3 do\n  if i then"));
  EXPECT_FALSE(open_after("for i = 1, 3 do\n  if i then x = i elseif y then else end\nend"));
  EXPECT_TRUE(open_after("while x do"));
  EXPECT_TRUE(open_after("repeat x = x + 1"));
  EXPECT_TRUE(open_after("repeat x = x + 1 until"));
  EXPECT_FALSE(open_after("repeat x = x + 1 until x > 3"));
  EXPECT_TRUE(open_after("t = {1,\n2,"));
  EXPECT_FALSE(open_after("t = {1,\n2}"));
  EXPECT_TRUE(open_after("print((1"));
  EXPECT_TRUE(open_after("x = 1 +"));
  EXPECT_TRUE(open_after("x = a and"));
  EXPECT_TRUE(open_after("x ="));
  EXPECT_TRUE(open_after("local"));
  EXPECT_FALSE(open_after("x = 1e+5"));
  EXPECT_FALSE(open_after("x = 0x1p-4"));
  EXPECT_FALSE(open_after("f(...)"));
  EXPECT_FALSE(open_after("::top:: goto top"));
  EXPECT_FALSE(open_after("x = t.x ; "));
  EXPECT_FALSE(open_after("end"));  // more ends than blocks: an error for the parser
}

}  // namespace
