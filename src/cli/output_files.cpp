#include "output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>

#include <fmt/format.h>

#include "bladestab/base/input_error.hpp"
#include "support/message_text.hpp"
#include "interruption.hpp"

namespace bladestab::cli {
namespace {

namespace fs = std::filesystem;

// ".campbell.png.4711-3.tmp.png" beside "campbell.png": hidden, unique to this process, and with
// the final extension (matplotlib chooses the format by it).
std::string temporary_for(const std::string& path) {
  static int serial = 0;
  const fs::path p(path);
  const std::string name = fmt::format(".{}.{}-{}.tmp{}", p.filename().string(), ::getpid(), serial++,
                                       p.extension().string());
  return (p.parent_path() / name).string();
}

}  // namespace

void check_file_stem(const std::string& name) {
  static const std::regex stem("[A-Za-z0-9_+][A-Za-z0-9._+-]*");
  if (name.size() > 200 || !std::regex_match(name, stem)) {
    throw InputError(fmt::format("--name {}: must be a file stem of at most 200 letters, digits, '.', '_', '+' and "
                                 "'-', not starting with '.' or '-' (no '/', spaces or control characters)",
                                 echoed(name)));
  }
}

void check_output_directory(const std::string& option, const std::string& dir) {
  const std::string shown = fmt::format("{} {}", option, echoed(dir, 240));
  if (dir.empty()) throw InputError(fmt::format("{}: must name a directory", shown));
  // Every query with an error code: a name the system refuses (too long, a loop of links) is bad
  // input like any other.
  std::error_code created, found;
  const fs::path folder(dir);
  fs::create_directories(folder, created);
  const fs::file_status status = fs::status(folder, found);
  if (!fs::is_directory(status)) {
    throw InputError(fmt::format("{}: cannot write into it: {}", shown,
                                 fs::exists(status) ? "it is not a directory"
                                 : created          ? created.message()
                                 : found            ? found.message()
                                                    : "it cannot be created"));
  }
  // The only sure test of writing is to write.
  const std::string probe = temporary_for((folder / "probe").string());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) throw InputError(fmt::format("{}: cannot write into it: {}", shown, std::strerror(errno)));
  ::close(fd);
  ::unlink(probe.c_str());
}

OutputFiles::~OutputFiles() {
  for (const Entry& e : entries_) {
    std::error_code ec;
    fs::remove(e.temporary, ec);
    forget_temporary(e.slot);
  }
}

std::string OutputFiles::reserve(const std::string& path) {
  Entry e{path, temporary_for(path), -1};
  e.slot = remember_temporary(e.temporary);
  entries_.push_back(e);
  return e.temporary;
}

std::string OutputFiles::write(const std::string& path, const std::string& text) {
  const std::string temporary = reserve(path);
  std::ofstream out(temporary, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw InputError(fmt::format("{}: cannot write this file: {}", echoed(path, 240), std::strerror(errno)));
  return temporary;
}

std::vector<std::string> OutputFiles::commit() {
  // A stop (Ctrl-C, the deadline) waits until the set is renamed: all of it or none.
  const StopDeferral deferral;
  // Renaming onto a directory is the one way a rename in place fails: found before any is renamed.
  for (const Entry& e : entries_) {
    std::error_code unknown;  // a path that cannot be queried fails at its rename below
    if (fs::is_directory(e.path, unknown)) {
      throw InputError(fmt::format("{}: cannot write this file: it is a directory", echoed(e.path, 240)));
    }
  }
  std::vector<std::string> written;
  for (Entry& e : entries_) {
    std::error_code ec;
    fs::rename(e.temporary, e.path, ec);
    if (ec) throw InputError(fmt::format("{}: cannot write this file: {}", echoed(e.path, 240), ec.message()));
    forget_temporary(e.slot);
    e.slot = -1;
    written.push_back(e.path);
  }
  entries_.clear();
  note_files_written();
  return written;
}

}  // namespace bladestab::cli
