// A line on the terminal that says how far a long computation is and about how long it still
// needs: "  dynamics p62: speed 37 of 120 (31 %), about 1 min 23 s left". Standard error only,
// only when it is a terminal and this is the first MPI process (or there is none), once the
// work has taken a second, at most four redraws a second; the line is wiped when the Progress
// ends, so logs and pipes never see it. Thread-safe: jobs on several threads advance the same
// Progress. A log written to the same terminal meanwhile should wipe the line before each of
// its lines (LineWipingBuffer).
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <stdexcept>
#include <streambuf>
#include <string>

namespace gearkit
{
/// A long computation stopped from outside (interrupt(): the Python module's Ctrl-C) at its next
/// progress step.
class Interrupted : public std::runtime_error
{
public:
  Interrupted();
};

/// Asks every running computation to stop: from now on every Progress::advance (and note), in
/// whatever thread, throws Interrupted - the work unwinds as after any error, nothing
/// half-written is kept - until clear_interrupt(). Safe from any thread.
void
interrupt();
void
clear_interrupt();
bool
interrupted();

class Progress
{
public:
  /// `what` names the work ("dynamics p62: speed"), `total` its steps (> 0).
  Progress(std::string what, std::size_t total);
  ~Progress();
  Progress(const Progress &) = delete;
  Progress &
  operator=(const Progress &) = delete;

  /// n more steps done; `doing` (optional) says what comes next ("gear: factorising").
  /// Throws Interrupted once interrupt() was called.
  void
  advance(std::size_t n = 1, const std::string &doing = "");
  /// Only a new note, no step.
  void
  note(const std::string &doing)
  {
    advance(0, doing);
  }

  /// Whether progress lines are drawn in this process (a terminal on standard error, the first
  /// MPI process, GEARKIT_PROGRESS not 0).
  static bool
  shown();

  /// "1 min 23 s", "42 s", "2 h 5 min".
  static std::string
  duration(double seconds);

private:
  void
  draw(bool force);

  std::string                           what;
  std::size_t                           total;
  std::atomic<std::size_t>              done{0};
  std::string                           doing;
  std::mutex                            guard;
  std::chrono::steady_clock::time_point start, last_draw;
  bool                                  visible;
  std::size_t                           width = 0; // of the line drawn last
};

/// A stream buffer that passes everything on to `to` and starts each line with the terminal's
/// "erase the line" (where a progress line may stand): the driver's log goes through it when
/// progress lines are shown.
class LineWipingBuffer : public std::streambuf
{
public:
  explicit LineWipingBuffer(std::streambuf *to)
      : to(to)
  {
  }

protected:
  int
  overflow(int c) override;
  int
  sync() override
  {
    return to->pubsync();
  }

private:
  std::streambuf *to;
  bool            line_start = true;
};
} // namespace gearkit
