// frame_writer.cpp — the writer thread and the progress bar (see
// frame_writer.h).
#include "render/frame_writer.h"

#include "io/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace clr {

FrameWriter::FrameWriter(size_t capacity, std::function<void(size_t)> onWritten)
    : capacity_(std::max<size_t>(capacity, 1)), onWritten_(std::move(onWritten)), thread_([this] { run(); })
{
}

FrameWriter::~FrameWriter()
{
  stop();
}

void FrameWriter::push(Frame frame)
{
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < capacity_ || failure_; });
  if (failure_) std::rethrow_exception(failure_);
  queue_.push_back(std::move(frame));
  changed_.notify_all();
}

void FrameWriter::finish()
{
  stop();
  if (failure_) std::rethrow_exception(failure_);
}

void FrameWriter::stop()
{
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void FrameWriter::run()
{
  for (;;) {
    // Step 1: the next frame, or the end.
    Frame frame;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || closed_; });
      if (queue_.empty()) return;
      frame = std::move(queue_.front());
      queue_.pop_front();
    }
    changed_.notify_all();
    // Step 2: encode and write it; a failure ends the thread.
    const auto start = std::chrono::steady_clock::now();
    try {
      writePng(frame.path, frame.width, frame.height, frame.rgba);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      failure_ = std::current_exception();
      queue_.clear();
      changed_.notify_all();
      return;
    }
    writeMs_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    if (onWritten_) onWritten_(++written_);
  }
}

std::string progressLine(size_t done, size_t total, double elapsedS)
{
  // Step 1: the bar, 24 cells.
  const size_t cells = 24;
  const size_t full = total ? std::min(cells, done * cells / total) : cells;
  std::string line = "[" + std::string(full, '#') + std::string(cells - full, '.') + "] ";
  // Step 2: counts, rate and time left (unknown until a frame is done).
  char text[128];
  const double fps = elapsedS > 0.0 ? done / elapsedS : 0.0;
  std::snprintf(text, sizeof text, "%zu/%zu frames  %.1f frames/s  ", done, total, fps);
  line += text;
  if (done == 0 || fps <= 0.0) return line + "ETA --:--";
  const long left = std::lround((total - std::min(done, total)) / fps);
  if (left >= 3600)
    std::snprintf(text, sizeof text, "ETA %ld:%02ld:%02ld", left / 3600, left / 60 % 60, left % 60);
  else
    std::snprintf(text, sizeof text, "ETA %ld:%02ld", left / 60, left % 60);
  return line + text;
}

ProgressBar::ProgressBar(size_t total, bool enabled, FILE* out) : total_(total), enabled_(enabled), out_(out) {}

bool ProgressBar::stderrIsTerminal()
{
  return isatty(STDERR_FILENO) == 1;
}

void ProgressBar::update(size_t done)
{
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  done_ = done;
  const auto now = std::chrono::steady_clock::now();
  if (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100) && done < total_) return;
  draw(done);
}

void ProgressBar::finish()
{
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  draw(done_);
  std::fputc('\n', out_);
  std::fflush(out_);
}

void ProgressBar::draw(size_t done)
{
  lastDraw_ = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(lastDraw_ - start_).count();
  // Trailing spaces clear what a longer previous line left behind.
  std::fprintf(out_, "\r%s   ", progressLine(done, total_, elapsed).c_str());
  std::fflush(out_);
  drawn_ = true;
}

}  // namespace clr
