// One array of records in key order, rewritten in place by a walk that reads last step's records
// from the front while it writes this step's behind them: the narrow phase's contacts and pairs
// apart need one array each instead of two (last step's and this step's). A contact is 480 bytes
// and a heap of 8,000 spheres keeps 21,000 of them, so the second array was 10 MB touched every
// step.
//
// The write position never passes the read position. Where this step has more records than last
// step so far (new contacts), the next unread record would be overwritten: it moves to a spill
// queue first, which keeps key order because every spilled record comes before those still in the
// array. Reads take the queue first. Once this step is k records ahead, each write moves one record
// through the queue, so the queue is a ring of k records, not a list of all that passed through.
// A record read is gone from the walk's point of view: its slot may be written next, so a caller
// that needs it while writing copies it out first.
#pragma once

#include <collide/hooks.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>

namespace collide::detail {

template <typename Record>
class InPlaceMerge {
  // A slot is made anew over its old record without destroying it.
  static_assert(std::is_trivially_destructible_v<Record>);

 public:
  // `records` holds last step's records; `spill` is scratch (its contents unspecified, its capacity
  // kept from step to step).
  InPlaceMerge(Array<Record>& records, Array<Record>& spill)
      : records_(records), spill_(spill), readEnd_(records.size()) {}
  InPlaceMerge(const InPlaceMerge&) = delete;
  InPlaceMerge& operator=(const InPlaceMerge&) = delete;

  // Last step's records, in key order.
  bool hasNext() const { return spillCount_ > 0 || read_ < readEnd_; }
  const Record& next() const { return spillCount_ > 0 ? spill_[spillHead_] : records_[read_]; }
  void pop() {
    if (spillCount_ > 0) {
      if (++spillHead_ == spill_.size()) spillHead_ = 0;
      --spillCount_;
    } else {
      ++read_;
    }
  }
  // The unread record `ahead` places on in the array (for prefetching), or null.
  const Record* unreadAhead(std::size_t ahead) const {
    return read_ + ahead < readEnd_ ? &records_[read_ + ahead] : nullptr;
  }

  // This step's next record, made from `args`, which may be a record of last step's (next(), or
  // one just read): where room must be made first (the next unread record spilled, or the array
  // grown), which can move or overwrite such a record, the new one is made aside first.
  template <typename... Args>
  Record& emplace(Args&&... args) {
    if ((write_ == read_ && read_ < readEnd_) || write_ == records_.size()) {
      const Record made(std::forward<Args>(args)...);
      if (write_ == read_ && read_ < readEnd_) spill(records_[read_++]);
      if (write_ == records_.size()) records_.emplace_back();
      return *std::construct_at(&records_[write_++], made);
    }
    // Otherwise the slot is one already read (its record copied out or kept, see keep()), and no
    // unread record lies there.
    return *std::construct_at(&records_[write_++], std::forward<Args>(args)...);
  }
  // Last step's record `previous` (next() a moment ago) kept as this step's next record: where the
  // walk writes into the very slot it read it from (a steady pile), nothing is copied.
  Record& keep(const Record& previous) {
    if (write_ < records_.size() && &previous == &records_[write_]) return records_[write_++];
    return emplace(previous);
  }
  // Takes back the record emplace() made last (the record turned out not to be kept).
  void dropLast() { --write_; }
  // The slot `ahead` places after the next one written, if the array has it (for prefetching).
  const Record* slotAhead(std::size_t ahead) const {
    return write_ + ahead < records_.size() ? &records_[write_ + ahead] : nullptr;
  }

  // After the walk: the array holds this step's records alone (last step's not read are dropped).
  void finish() { records_.resize(write_); }

 private:
  void spill(const Record& record) {
    if (spillCount_ == spill_.size()) {
      // Full: the ring is laid out from its head again and doubled.
      std::rotate(spill_.begin(), spill_.begin() + static_cast<std::ptrdiff_t>(spillHead_), spill_.end());
      spillHead_ = 0;
      spill_.resize(std::max<std::size_t>(16, 2 * spill_.size()));
    }
    std::size_t at = spillHead_ + spillCount_;
    if (at >= spill_.size()) at -= spill_.size();
    spill_[at] = record;
    ++spillCount_;
  }

  Array<Record>& records_;
  Array<Record>& spill_;
  std::size_t readEnd_;   // last step's records in the array are [read_, readEnd_)
  std::size_t read_ = 0;  // and those in the spill ring (spillCount_ from spillHead_) come first
  std::size_t spillHead_ = 0;
  std::size_t spillCount_ = 0;
  std::size_t write_ = 0;  // this step's records are [0, write_)
};

}  // namespace collide::detail
