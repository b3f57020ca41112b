// The one exception type of P4. It is thrown only at the edges (files, devices, options), never in
// the per-frame path; its message names the file, field or value that is wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace p4 {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace p4
