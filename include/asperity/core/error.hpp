#pragma once
// Error types of the library: every failure is one of these, never a silent NaN.
#include <stdexcept>
#include <string>

namespace asperity {

/// Base of every exception thrown by asperity.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad user data; the message names the field, its value and what is allowed.
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A solve or an integral that failed; the message says what was tried.
class NumericalError : public Error {
 public:
  using Error::Error;
};

}  // namespace asperity
