// The REPL's history file, $HOME/.rigidlab_history, read at start and rewritten after every
// chunk (through a temporary file and a rename, so an interrupted write never leaves it
// truncated). A symbolic link there is written through: the file it leads to is rewritten
// (or created, for a link whose target does not exist yet), never the link itself. A target
// that is not a regular file (a link to /dev/null to keep no history, a FIFO, a directory)
// is left alone: neither read (a FIFO would block) nor replaced.
#pragma once

#include <string>

namespace rigidlab::cli {

class HistoryFile {
 public:
  HistoryFile();  // finds the file; without HOME there is none: the history lasts a session
  // Reads the file into libedit's history, if it is a regular file.
  void load() const;
  // Writes libedit's history to the file. Says once on stderr why, when it cannot.
  void save();

 private:
  std::string path_;   // where the links lead; "" without HOME
  std::string error_;  // why the links cannot be followed (a loop), if so
  bool failed_ = false;
};

}  // namespace rigidlab::cli
