# Finds every dependency among Debian 12's packages. A missing one stops configuration with
# the apt-get line that installs it, so a new user is never left guessing.

function(rigidlab_missing what package)
  message(FATAL_ERROR
    "rigidlab needs ${what}, which was not found.\n"
    "Install it with:  apt-get install ${package}\n"
    "(or install everything at once: see the Quick start in README.md)")
endfunction()

# Eigen 3 (header only)
find_package(Eigen3 3.3 QUIET NO_MODULE)
if(NOT TARGET Eigen3::Eigen)
  rigidlab_missing("Eigen 3" libeigen3-dev)
endif()

# Lua 5.4, the build compiled as C++: a Lua error unwinds C++ frames with an exception instead
# of longjmp, so destructors in the bindings always run. The static archive is preferred:
# start-up time is a goal (within 1.5x of bare lua5.4), and dynamic loading is most of it.
find_path(RIGIDLAB_LUA_INCLUDE_DIR lua.hpp PATH_SUFFIXES lua5.4)
find_library(RIGIDLAB_LUA_LIBRARY NAMES liblua5.4-c++.a lua5.4-c++)
if(NOT RIGIDLAB_LUA_INCLUDE_DIR OR NOT RIGIDLAB_LUA_LIBRARY)
  rigidlab_missing("Lua 5.4 (headers and the C++ build of the library)" liblua5.4-dev)
endif()
add_library(Rigidlab::Lua INTERFACE IMPORTED)
set_target_properties(Rigidlab::Lua PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${RIGIDLAB_LUA_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${RIGIDLAB_LUA_LIBRARY};m;dl")

# libedit: line editing and history for the REPL. As for Lua, the static archives are
# preferred when all are there (libedit-dev pulls in libncurses-dev, libbsd-dev, libmd-dev):
# loading libedit and its three shared dependencies cost a third of `rigidlab -e ''`.
find_path(RIGIDLAB_EDIT_INCLUDE_DIR editline/readline.h)
find_library(RIGIDLAB_EDIT_LIBRARY NAMES edit)
if(NOT RIGIDLAB_EDIT_INCLUDE_DIR OR NOT RIGIDLAB_EDIT_LIBRARY)
  rigidlab_missing("libedit (line editing)" libedit-dev)
endif()
set(RIGIDLAB_EDIT_LINK "${RIGIDLAB_EDIT_LIBRARY}")
find_library(RIGIDLAB_EDIT_STATIC NAMES libedit.a)
find_library(RIGIDLAB_TINFO_STATIC NAMES libtinfo.a)
find_library(RIGIDLAB_BSD_STATIC NAMES libbsd.a)
find_library(RIGIDLAB_MD_STATIC NAMES libmd.a)
if(RIGIDLAB_EDIT_STATIC AND RIGIDLAB_TINFO_STATIC AND RIGIDLAB_BSD_STATIC AND RIGIDLAB_MD_STATIC)
  set(RIGIDLAB_EDIT_LINK
      "${RIGIDLAB_EDIT_STATIC};${RIGIDLAB_TINFO_STATIC};${RIGIDLAB_BSD_STATIC};${RIGIDLAB_MD_STATIC}")
endif()
add_library(Rigidlab::Edit INTERFACE IMPORTED)
set_target_properties(Rigidlab::Edit PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${RIGIDLAB_EDIT_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${RIGIDLAB_EDIT_LINK}")

# GoogleTest
find_package(GTest QUIET)
if(NOT TARGET GTest::gtest_main)
  rigidlab_missing("GoogleTest" libgtest-dev)
endif()

# Google Benchmark
find_package(benchmark QUIET)
if(NOT TARGET benchmark::benchmark)
  rigidlab_missing("Google Benchmark" libbenchmark-dev)
endif()

find_package(Threads REQUIRED)

# Chromium: w:export_html's page is loaded in the headless browser by tests/present.
find_program(RIGIDLAB_CHROMIUM NAMES chromium chromium-browser)
if(NOT RIGIDLAB_CHROMIUM)
  rigidlab_missing("chromium (the browser test of w:export_html's page)" chromium)
endif()
