// Warnings about the numerical validity of a result (issue 9's stability campaign).
//
// A backend that produces a result it cannot vouch for — an FDTD run near its Courant limit, a
// BEM mesh too coarse for the wavelength, a fit whose lobe has no energy to fit — still returns
// the result, and raises a warning here. The warning is printed on stderr the first time its
// code is raised in a run (unless echo is off: `plumage -q`), and every file the run writes
// carries the run's warnings in its metadata (docs/formats.md), so a result is never silently
// wrong. Warnings are collected per process; the CLI clears them at the start of a command.
//
// Codes are stable dotted identifiers "<backend>.<condition>" (e.g. "fdtd.courant",
// "bem.mesh_coarse"); tests assert on codes, people read messages. A code raised many times is
// kept once with a count and the lexicographically smallest of its messages (the first raise is
// the one echoed; the kept text does not depend on which thread raised first, so metadata written
// from it is deterministic), so a warning inside a per-entry loop costs one mutex and a scan of a
// short list, not a growing list.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace plumage {

struct Warning {
  std::string code;
  std::string message;     // the smallest of its raises' messages (deterministic under threads)
  std::size_t count = 1;   // raises of this code since the last clear()
};

class Diagnostics {
 public:
  // Thread-safe. The first raise of a code is echoed as "warning: <message> [<code>]"; its kept
  // message is the smallest raised.
  void warn(std::string_view code, std::string message);

  std::vector<Warning> warnings() const;  // in order of first raise
  bool has(std::string_view code) const;
  bool empty() const;
  // "<code>: <message>" plus " (raised N times)" when N > 1, per code, each followed by
  // `terminator`; "" when none. With terminator "; " it fits one metadata line.
  std::string summary(std::string_view terminator = "\n") const;
  void clear();
  // Where first raises are echoed: &std::cerr by default, nullptr for none.
  void set_echo(std::ostream* stream);

  Diagnostics();
  ~Diagnostics();
  Diagnostics(const Diagnostics&) = delete;
  Diagnostics& operator=(const Diagnostics&) = delete;

 private:
  struct State;
  State* state_;
};

// The process's diagnostics.
Diagnostics& diagnostics();

// Shorthand for diagnostics().warn(code, message).
void warn(std::string_view code, std::string message);

// Where a warning was raised (issue 23: a warning says where and how much). warn_at() raises
// like warn() and also tells the innermost WarningSites alive on the calling thread which item
// (e.g. the index of an incident azimuth in one solve) raised it and a measure of how far
// beyond the limit it was. A caller that knows what the items are (the work group knows its
// units, simulate its instances) opens a WarningSites around the call; without one, warn_at()
// is warn(). Scopes nest (a thread that steals another task while waiting inside one gets its
// own scope and then restores the outer one), so a site always lands in the scope of the task
// that raised it, whatever the scheduling.
struct WarningSite {
  enum class Item { azimuth, instance };  // what `item` indexes
  std::string code;
  Item kind = Item::instance;
  std::size_t item = 0;
  double value = 0.0;  // the raise's measure (e.g. the horizon spill ratio); may be +inf
};
class WarningSites {
 public:
  WarningSites();
  ~WarningSites();
  WarningSites(const WarningSites&) = delete;
  WarningSites& operator=(const WarningSites&) = delete;
  const std::vector<WarningSite>& sites() const { return sites_; }
  void add(WarningSite site) { sites_.push_back(std::move(site)); }

 private:
  std::vector<WarningSite> sites_;
  WarningSites* outer_ = nullptr;
};
void warn_at(std::string_view code, std::string message, WarningSite::Item kind, std::size_t item, double value);

// For tests and tools: for its lifetime the process's diagnostics start empty and their echo goes
// into echoed() instead of stderr; on destruction (also when a test check throws) the echo returns
// to std::cerr and the warnings are cleared.
class CapturedWarnings {
 public:
  CapturedWarnings();
  ~CapturedWarnings();
  CapturedWarnings(const CapturedWarnings&) = delete;
  CapturedWarnings& operator=(const CapturedWarnings&) = delete;

  std::string echoed() const;                        // everything echoed so far
  bool echoed(std::string_view code) const;          // "warning: … [<code>]" was echoed
  std::size_t count(std::string_view code) const;    // raises of `code` so far, 0 if none
  std::string message(std::string_view code) const;  // its kept message, "" if none

 private:
  std::unique_ptr<std::ostringstream> echo_;
};

}  // namespace plumage
