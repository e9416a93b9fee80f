#include "plumage/diagnostics.hpp"

#include <iostream>
#include <mutex>
#include <sstream>

namespace plumage {

struct Diagnostics::State {
  mutable std::mutex mutex;
  std::vector<Warning> warnings;
  std::ostream* echo = &std::cerr;
};

Diagnostics::Diagnostics() : state_(new State) {}
Diagnostics::~Diagnostics() { delete state_; }

void Diagnostics::warn(std::string_view code, std::string message) {
  // One line per warning: file headers store them as single-line metadata.
  for (char& c : message) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::lock_guard lock(state_->mutex);
  for (auto& w : state_->warnings) {
    if (w.code == code) {
      ++w.count;
      return;
    }
  }
  if (state_->echo) *state_->echo << "warning: " << message << " [" << code << "]\n" << std::flush;
  state_->warnings.push_back({std::string(code), std::move(message), 1});
}

std::vector<Warning> Diagnostics::warnings() const {
  std::lock_guard lock(state_->mutex);
  return state_->warnings;
}

bool Diagnostics::has(std::string_view code) const {
  std::lock_guard lock(state_->mutex);
  for (const auto& w : state_->warnings) {
    if (w.code == code) return true;
  }
  return false;
}

bool Diagnostics::empty() const {
  std::lock_guard lock(state_->mutex);
  return state_->warnings.empty();
}

std::string Diagnostics::summary(std::string_view terminator) const {
  std::lock_guard lock(state_->mutex);
  std::ostringstream out;
  for (const auto& w : state_->warnings) {
    out << w.code << ": " << w.message;
    if (w.count > 1) out << " (raised " << w.count << " times)";
    out << terminator;
  }
  return out.str();
}

void Diagnostics::clear() {
  std::lock_guard lock(state_->mutex);
  state_->warnings.clear();
}

void Diagnostics::set_echo(std::ostream* stream) {
  std::lock_guard lock(state_->mutex);
  state_->echo = stream;
}

Diagnostics& diagnostics() {
  // Never destroyed: plug-ins may raise warnings from static destructors' threads.
  static Diagnostics* instance = new Diagnostics;
  return *instance;
}

void warn(std::string_view code, std::string message) { diagnostics().warn(code, std::move(message)); }

}  // namespace plumage
