#include "base/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace gearkit
{
int
LineWipingBuffer::overflow(int c)
{
  if (c == traits_type::eof())
    return to->pubsync() == 0 ? 0 : traits_type::eof();
  if (line_start && to->sputn("\r\033[2K", 5) != 5)
    return traits_type::eof();
  line_start = c == '\n';
  return to->sputc(char(c));
}

bool
Progress::shown()
{
  static const bool on = [] {
    const char *env = std::getenv("GEARKIT_PROGRESS");
    if (env && std::string(env) == "0")
      return false;
    // mpirun tells each process its rank; only the first draws
    for (const char *rank : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"})
      if (const char *r = std::getenv(rank); r && std::atoi(r) != 0)
        return false;
    return isatty(STDERR_FILENO) == 1;
  }();
  return on;
}

std::string
Progress::duration(double seconds)
{
  const long s = std::lround(std::max(0.0, seconds));
  char       text[48];
  if (s < 60)
    std::snprintf(text, sizeof text, "%ld s", s);
  else if (s < 3600)
    std::snprintf(text, sizeof text, "%ld min %ld s", s / 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%ld h %ld min", s / 3600, (s % 3600) / 60);
  return text;
}

Progress::Progress(std::string what_, std::size_t total_)
    : what(std::move(what_))
    , total(std::max<std::size_t>(1, total_))
    , start(std::chrono::steady_clock::now())
    , last_draw(start)
    , visible(shown())
{
}

Progress::~Progress()
{
  if (visible && width > 0)
    std::fprintf(stderr, "\r%*s\r", int(width), "");
}

namespace
{
std::atomic<bool> interrupt_requested{false};
} // namespace

Interrupted::Interrupted()
    : std::runtime_error("interrupted")
{
}

void
interrupt()
{
  interrupt_requested = true;
}

void
clear_interrupt()
{
  interrupt_requested = false;
}

bool
interrupted()
{
  return interrupt_requested;
}

void
Progress::advance(std::size_t n, const std::string &doing_)
{
  if (interrupt_requested)
    throw Interrupted();
  done += n;
  if (!visible)
    return;
  std::lock_guard<std::mutex> lock(guard);
  if (!doing_.empty())
    doing = doing_;
  draw(!doing_.empty());
}

void
Progress::draw(bool force)
{
  if (!visible)
    return;
  const auto now = std::chrono::steady_clock::now();
  // nothing for work done within a second; then at most four redraws a second
  if (now - start < std::chrono::seconds(1) ||
      (!force && now - last_draw < std::chrono::milliseconds(250)))
    return;
  last_draw                = now;
  const std::size_t d      = std::min(done.load(), total);
  const double      passed = std::chrono::duration<double>(now - start).count();
  std::string line = "  " + what + " " + std::to_string(d) + " of " + std::to_string(total) + " (" +
                     std::to_string(100 * d / total) + " %)";
  if (d > 0 && d < total)
    line += ", about " + duration(passed * double(total - d) / double(d)) + " left";
  if (!doing.empty())
    line += ": " + doing;
  if (line.size() > 120)
    line.resize(120);
  // over the line drawn last (a log on standard output wipes it first: LineWipingBuffer)
  std::fprintf(stderr, "\r%-*s", int(std::max(width, line.size())), line.c_str());
  std::fflush(stderr);
  width = line.size();
}
} // namespace gearkit
