#pragma once
// The files a command writes, as one set. Each is written to a temporary beside its final name
// and the set is renamed into place only when every file of it is complete, so an error, a full
// disk or Ctrl-C leaves the previous files (or none), never part of a set. Until then the
// temporaries are known to interruption.hpp, which removes them if the run is stopped.
#include <string>
#include <vector>

namespace bladestab::cli {

// `option value` (e.g. "--out maps"): the directory is created if missing; InputError unless a file
// can be created in it. Commands call it before computing, so a bad --out costs nothing.
void check_output_directory(const std::string& option, const std::string& dir);

// --name STEM names files: letters, digits, '.', '_', '+' and '-', not starting with '.' or '-'
// (a hidden file, an option); no '/', spaces, quotes or control characters. InputError otherwise.
void check_file_stem(const std::string& name);

class OutputFiles {
public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles();  // removes the temporaries of a set not committed

  // Writes `text` to the temporary of `path` and returns the temporary's name; InputError if that
  // fails.
  std::string write(const std::string& path, const std::string& text);
  // The temporary of `path` for a writer of its own (the chart drawer, Matrix Market): same
  // directory, same extension.
  std::string reserve(const std::string& path);
  // Renames every temporary to its final name; returns the final names, in the order added.
  std::vector<std::string> commit();

private:
  struct Entry {
    std::string path, temporary;
    int slot = -1;  // in interruption.hpp's registry
  };
  std::vector<Entry> entries_;
};

}  // namespace bladestab::cli
