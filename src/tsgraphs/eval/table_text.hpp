#pragma once
/// Numbers and fields as the tables print them (the demo's, the suite's, the HTML reports').
#include <string>

namespace tsgraphs::eval {

/// `v` with `decimals` digits after the point, whatever the locale; a value that rounds to zero
/// prints as 0, never -0.
std::string fixed_text(double v, int decimals);

/// A CSV field, quoted (quotes doubled) when it holds a separator, a quote or a line break.
std::string csv_field(const std::string& text);

}  // namespace tsgraphs::eval
