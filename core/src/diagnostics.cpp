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
      // Keep the smallest message, not the first: which instance or thread raises first depends
      // on scheduling, the set of messages does not, so files written from the summary are the
      // same on 1 or 2 threads.
      if (message < w.message) w.message = std::move(message);
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

namespace {
thread_local WarningSites* innermost_sites = nullptr;
}  // namespace

WarningSites::WarningSites() : outer_(innermost_sites) { innermost_sites = this; }
WarningSites::~WarningSites() { innermost_sites = outer_; }

void warn_at(std::string_view code, std::string message, WarningSite::Item kind, std::size_t item, double value) {
  if (innermost_sites) innermost_sites->add({std::string(code), kind, item, value});
  diagnostics().warn(code, std::move(message));
}

CapturedWarnings::CapturedWarnings() : echo_(std::make_unique<std::ostringstream>()) {
  diagnostics().clear();
  diagnostics().set_echo(echo_.get());
}

CapturedWarnings::~CapturedWarnings() {
  diagnostics().set_echo(&std::cerr);
  diagnostics().clear();
}

std::string CapturedWarnings::echoed() const { return echo_->str(); }

bool CapturedWarnings::echoed(std::string_view code) const {
  const std::string s = echo_->str();
  return s.find("warning: ") != std::string::npos && s.find("[" + std::string(code) + "]") != std::string::npos;
}

std::size_t CapturedWarnings::count(std::string_view code) const {
  for (const auto& w : diagnostics().warnings())
    if (w.code == code) return w.count;
  return 0;
}

std::string CapturedWarnings::message(std::string_view code) const {
  for (const auto& w : diagnostics().warnings())
    if (w.code == code) return w.message;
  return {};
}

}  // namespace plumage
