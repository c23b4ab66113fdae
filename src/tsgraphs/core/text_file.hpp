#pragma once
/// Reading a whole file, the one way every reader of the project does it.
#include <string>

namespace tsgraphs {

/// The file's bytes. A missing file, a folder or a file that cannot be read is an InputError
/// naming the path: "cannot open file", or `what_is_wrong` when given.
std::string read_text_file(const std::string& path, const std::string& what_is_wrong = "cannot open file");

}  // namespace tsgraphs
