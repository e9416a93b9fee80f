// Error types. Every error a user can cause names where it came from.
#pragma once

#include <stdexcept>
#include <string>

namespace plumage {

// Base of all plumage errors.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A place in a configuration file (1-based line and column; 0 when unknown).
struct SourceMark {
  std::string file;
  int line = 0;
  int column = 0;

  // "file:line:column", or "file" when the line is unknown.
  std::string str() const;
};

// Bad input in a configuration: unknown key, wrong type, out-of-range value, missing file,
// unknown plug-in type. what() reads "file:line:column: field: message".
class ConfigError : public Error {
 public:
  ConfigError(SourceMark mark, std::string field, std::string message);

  const SourceMark& mark() const { return mark_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

 private:
  SourceMark mark_;
  std::string field_;
  std::string message_;
};

// A plug-in library that cannot be used: missing file, missing symbol, wrong ABI, wrong kind.
class PluginError : public Error {
 public:
  using Error::Error;
};

// A computation that detected its own failure (instability, non-finite result...).
class NumericalError : public Error {
 public:
  using Error::Error;
};

}  // namespace plumage
