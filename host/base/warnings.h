// warnings.h — the one sink every warning goes through, bounded whatever
// the input.
//
// A warning has a kind (what repeats: "a material library not found") and
// a line (the first one of its kind, naming the file). Each kind keeps only
// its first line, which ends in " (and 99,999 more like it)" once the kind
// repeats. The lines together stay within kMaxBytes: a new kind past that
// is only counted, in a last line "and N more warnings". So a model naming
// 100,000 missing material libraries gives one line, and any input at most
// about 4 KB of warnings; memory is bounded the same way (kinds past the
// bound are not kept).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace clr {

class Warnings {
 public:
  static constexpr size_t kMaxBytes = 4096;

  // Adds a warning `times` times; true when it made a new line (not a
  // repeat, within the bound).
  bool add(const std::string& kind, const std::string& line, size_t times = 1)
  {
    if (times == 0) return false;
    const auto found = kinds_.find(kind);
    if (found != kinds_.end()) {
      Entry& e = entries_[found->second];
      e.more += times;
      lines_[found->second] = e.line + " (and " + grouped(e.more) + " more like it)";
      return false;
    }
    if (line.empty() || bytes_ + line.size() > kMaxBytes) {
      if (dropped_ == 0) lines_.emplace_back();
      dropped_ += times;
      lines_.back() = "and " + grouped(dropped_) + " more warnings";
      return false;
    }
    bytes_ += line.size();
    kinds_.emplace(kind, entries_.size());
    entries_.push_back({line, 0});
    lines_.insert(lines_.begin() + long(entries_.size() - 1), line);
    if (times > 1) add(kind, line, times - 1);
    return true;
  }
  // A warning that is its own kind.
  bool add(const std::string& line) { return add(line, line); }
  // Every line of another sink, each as its own kind.
  void addAll(const Warnings& other)
  {
    for (const std::string& line : other.lines()) add(line);
  }

  // The lines: each kind's first line (with its repeat count), in order of
  // arrival, then "and N more warnings" when any were past the bound.
  const std::vector<std::string>& lines() const { return lines_; }
  bool empty() const { return lines_.empty(); }

  // n with a comma between groups of three digits (99,999).
  static std::string grouped(size_t n)
  {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
      if (i && (digits.size() - i) % 3 == 0) out += ',';
      out += digits[i];
    }
    return out;
  }

 private:
  struct Entry {
    std::string line;
    size_t more = 0;
  };
  std::map<std::string, size_t> kinds_;  // kind -> index in entries_ (and lines_)
  std::vector<Entry> entries_;
  std::vector<std::string> lines_;
  size_t bytes_ = 0, dropped_ = 0;
};

}  // namespace clr
