// frame_writer.h — overlaps PNG encoding and writing with rendering, and shows progress.
//
// FrameWriter owns one writer thread and a small bounded queue. The render loop push()es each finished image and goes
// on with the next frame while the thread encodes and writes the previous ones through writePng (a temporary file
// renamed into place, image_io.h). push() blocks while the queue is full, so at most capacity + 1 images wait in host
// memory. The first write failure stops the thread; push() and finish() rethrow it. Destroying a writer that was not
// finished writes what is queued unless a write failed, and never throws.
//
// ProgressBar redraws one line on a terminal ("\r" before each redraw, at most 10 redraws a second): frames done/total,
// frames per second and the time left. It draws nothing when disabled, i.e. when stderr is not a terminal. finish(), or
// the destructor, ends the line, so an error message after it starts on a line of its own.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace clr {

struct Frame {
  std::string path;
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> rgba;  // as writePng takes it
};

class FrameWriter {
 public:
  // onWritten(frames written so far) runs on the writer thread after each file.
  explicit FrameWriter(size_t capacity, std::function<void(size_t)> onWritten = {});
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  void push(Frame frame);
  // Waits until every pushed frame is written; rethrows a write failure.
  void finish();
  // Encode + write time of each written frame, in ms (valid after finish()).
  const std::vector<double>& writeMs() const { return writeMs_; }

 private:
  void run();
  void stop();

  const size_t capacity_;
  std::function<void(size_t)> onWritten_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;
  bool closed_ = false;
  std::exception_ptr failure_;
  size_t written_ = 0;
  std::vector<double> writeMs_;
  std::thread thread_;
};

// The text of one progress line (no "\r", no newline), for done of total
// frames after elapsedS seconds.
std::string progressLine(size_t done, size_t total, double elapsedS);

class ProgressBar {
 public:
  ProgressBar(size_t total, bool enabled, FILE* out = stderr);
  ~ProgressBar() { finish(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  // Whether stderr is a terminal (the bar's default).
  static bool stderrIsTerminal();
  void update(size_t done);  // thread-safe; redraws at most 10 times a second
  void finish();             // final redraw and newline, once drawn

 private:
  void draw(size_t done);

  const size_t total_;
  const bool enabled_;
  FILE* out_;
  std::mutex mutex_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point lastDraw_;
  size_t done_ = 0;
  bool drawn_ = false, finished_ = false;
};

}  // namespace clr
