#include "tsgraphs/core/text_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tsgraphs/core/error.hpp"

namespace tsgraphs {

std::string read_text_file(const std::string& path, const std::string& what_is_wrong) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!std::filesystem::is_regular_file(path, ec) || !in) throw input_error(path, 0, what_is_wrong);
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw input_error(path, 0, "cannot read file");
  return s.str();
}

}  // namespace tsgraphs
