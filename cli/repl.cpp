#include "cli/repl.hpp"

#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "cli/chunk_scanner.hpp"
#include "cli/interrupt.hpp"
#include "cli/limits.hpp"
#include "cli/line_reader.hpp"
#include "cli/run.hpp"
#include "cli/usage.hpp"

namespace rigidlab::cli {
namespace {

constexpr const char* chunkname = "=stdin";

// The prompt: the global _PROMPT (first line) or _PROMPT2 (continuation) if it is a string
// or a number, as in lua.c; read raw, so that no code of the user's runs at the prompt (an
// __index on _G that loops).
std::string prompt(lua_State* L, bool first_line) {
  lua_pushglobaltable(L);
  lua_pushstring(L, first_line ? "_PROMPT" : "_PROMPT2");
  lua_rawget(L, -2);
  lua_remove(L, -2);
  const char* custom = lua_isstring(L, -1) ? lua_tostring(L, -1) : nullptr;
  std::string result = custom != nullptr ? custom : first_line ? "> " : ">> ";
  lua_pop(L, 1);
  return result;
}

// A syntax error whose message ends in "<eof>": the chunk is incomplete, not wrong.
bool incomplete(lua_State* L, int status) {
  if (status != LUA_ERRSYNTAX) return false;
  size_t length = 0;
  const char* message = lua_tolstring(L, -1, &length);
  constexpr size_t mark = sizeof "<eof>" - 1;
  return length >= mark && std::strcmp(message + length - mark, "<eof>") == 0;
}

// Compiles `return <chunk>;` and leaves the function pushed when that works: the chunk is an
// expression list whose values are to be printed.
bool load_expression(lua_State* L, const std::string& chunk) {
  const std::string code = "return " + chunk + ";";
  if (load_text(L, code.data(), code.size(), chunkname) == LUA_OK) return true;
  lua_pop(L, 1);
  return false;
}

// An unfinished expression (`(1 +`): its `return` form ends in <eof> too.
bool incomplete_expression(lua_State* L, const std::string& chunk) {
  const std::string code = "return " + chunk;
  const bool result = incomplete(L, load_text(L, code.data(), code.size(), chunkname));
  lua_pop(L, 1);
  return result;
}

// Compiles the chunk under the limits (a huge chunk takes time and memory to compile), first
// as an expression, then as statements, and pushes the function or the error. Returns true
// when that ends the chunk: it compiled, or it is wrong otherwise than by being incomplete.
bool compile(lua_State* L, const std::string& chunk, int& status) {
  const TimedRun timed(L);
  if (load_expression(L, chunk)) {
    status = LUA_OK;
    return true;
  }
  status = load_text(L, chunk.data(), chunk.size(), chunkname);
  return !incomplete(L, status) &&
         !(status == LUA_ERRSYNTAX && incomplete_expression(L, chunk));
}

// A chunk that cannot be complete yet (cli/chunk_scanner.hpp) is compiled only while it is
// small or each time it has doubled: an error inside it is still found, and the work of all
// the compilations stays proportional to the chunk's length.
constexpr std::size_t small_chunk_bytes = 4096;

bool worth_compiling(const std::string& chunk, std::size_t compiled_size,
                     const ChunkScanner& scanner) {
  return chunk.size() <= small_chunk_bytes || !scanner.open() || chunk.size() >= 2 * compiled_size;
}

MemoryBudget* budget_of(lua_State* L) {
  LimitedState* state = LimitedState::of(L);
  return state != nullptr ? &state->budget() : nullptr;
}

// Reads and compiles one chunk: the function (or the syntax error) is pushed and `status` set.
// The lines read so far are tried as an expression, then as statements; while either is
// incomplete another line is read (a chunk on several lines behaves as on one). The chunk's
// text counts against the memory limit. Returns `interrupted` or `end` with nothing pushed.
ReadStatus read_chunk(lua_State* L, LineReader& reader, int& status) {
  std::string chunk;
  const ReadStatus first = reader.read(prompt(L, true).c_str(), chunk);
  if (first != ReadStatus::line) return first;
  if (chunk[0] == '=') chunk = "return " + chunk.substr(1);  // Lua 5.2's `=expression`
  ChunkScanner scanner;
  scanner.feed(chunk);
  std::size_t compiled_size = 0;
  MemoryBudget* budget = budget_of(L);
  try {
    for (;;) {
      if (worth_compiling(chunk, compiled_size, scanner)) {
        compiled_size = chunk.size();
        const ChargeHeap charge(budget);
        if (compile(L, chunk, status)) break;
        lua_pop(L, 1);
      }
      std::string more;  // the line editor is not charged: it is C, no exception may cross it
      const ReadStatus next = reader.read(prompt(L, false).c_str(), more);
      if (next == ReadStatus::interrupted) return next;  // Ctrl-C abandons the whole chunk
      const ChargeHeap charge(budget);
      if (next == ReadStatus::end) {  // report the "<eof>" error (or run what is complete)
        compile(L, chunk, status);
        break;
      }
      scanner.feed(more);
      chunk += '\n';
      chunk += more;
    }
  } catch (const std::bad_alloc&) {  // the chunk's text passed the memory limit
    lua_pushliteral(L, "not enough memory");  // Lua's own message: interned, nothing allocated
    status = LUA_ERRMEM;
    return ReadStatus::line;
  }
  reader.remember(chunk);
  return ReadStatus::line;
}

}  // namespace

void run_repl(lua_State* L, bool terminal) {
  const IgnoreStrayInterrupts stray_interrupts;
  const std::unique_ptr<LineReader> reader =
      terminal ? make_terminal_reader(L) : make_stream_reader();
  const Traceback traceback = terminal ? Traceback::append : Traceback::omit;
  if (terminal) std::printf("%s\n", banner().c_str());
  const int base = lua_gettop(L);
  for (;;) {
    lua_settop(L, base);
    int status = LUA_OK;
    const ReadStatus read = read_chunk(L, *reader, status);
    if (read == ReadStatus::end) break;
    if (read == ReadStatus::interrupted) continue;
    if (status != LUA_OK) {  // a syntax error, or the limits stopped the reading
      report_error(L, "");
      continue;
    }
    const TimedRun timed(L);  // the limits apply to each chunk
    status = call_chunk(L, 0, LUA_MULTRET, traceback);
    if (status == LUA_OK)
      print_results(L, base);
    else
      report_error(L, "");
  }
  lua_settop(L, base);
  std::fflush(stdout);
}

}  // namespace rigidlab::cli
