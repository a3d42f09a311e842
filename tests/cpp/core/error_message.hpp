#pragma once
// A test helper: the message of the std::invalid_argument a call throws, to check that bad input is named.
#include <functional>
#include <stdexcept>
#include <string>

namespace graspmix::test {

/// What `f` throws as std::invalid_argument, or "no error" when it throws nothing.
inline std::string error_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace graspmix::test
