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
//
// Several walks can rewrite one array at once, each over its own block of it (the records of its
// own pairs): a block's walk writes within the block, what does not fit goes to the block's
// overflow, and compactBlocks joins the blocks in order afterwards.
#pragma once

#include <collide/hooks.h>

#include "memory/scratch.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>
#include <utility>

namespace collide::detail {

// The first of `records` (in key order) whose key is not below `key`: where a walk that starts at
// `key` begins to read.
template <typename Record>
std::size_t firstAtOrAfter(std::span<const Record> records, std::uint64_t key) {
  return static_cast<std::size_t>(
      std::lower_bound(records.begin(), records.end(), key,
                       [](const Record& record, std::uint64_t k) { return record.key < k; }) -
      records.begin());
}

// One block of an array that several walks rewrite at once (InPlaceMerge's block constructor,
// compactBlocks), with the walk's scratch, kept from step to step.
template <typename Record>
struct MergeBlock {
  std::size_t begin = 0;  // last step's records of the block: [begin, end)
  std::size_t end = 0;
  std::size_t inPlace = 0;  // after the walk: this step's, written from begin, then the overflow
  Array<Record> spill;
  Array<Record> overflow;
};

template <typename Record>
class InPlaceMerge {
  // A slot is made anew over its old record without destroying it.
  static_assert(std::is_trivially_destructible_v<Record>);

 public:
  // `records` holds last step's records; `spill` is scratch (its contents unspecified, its capacity
  // kept from step to step). The walk rewrites the whole array, growing it as this step needs.
  InPlaceMerge(Array<Record>& records, Array<Record>& spill)
      : records_(records), spill_(spill), readEnd_(records.size()), limit_(records.size()) {}
  // A block of the array, [block.begin, block.end), rewritten by one of several walks at once (each
  // over its own block and pairs): this step's records are written from `begin` up to `end` at most,
  // and those beyond go to the block's overflow (emptied here); compactBlocks then closes the gaps.
  InPlaceMerge(Array<Record>& records, MergeBlock<Record>& block)
      : records_(records),
        spill_(block.spill),
        block_(&block),
        readEnd_(block.end),
        read_(block.begin),
        write_(block.begin),
        limit_(block.end) {
    block.overflow.clear();
  }
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
    lastOverflowed_ = false;
    if ((write_ == read_ && read_ < readEnd_) || write_ == limit_) {
      const Record made(std::forward<Args>(args)...);
      if (write_ == read_ && read_ < readEnd_) spill(records_[read_++]);
      if (write_ == limit_) {
        if (block_) {
          lastOverflowed_ = true;
          return block_->overflow.emplace_back(made);
        }
        // Grown as a vector grows (doubling), but without both blocks held whole (scratch.h).
        if (records_.size() == records_.capacity())
          growByStretches(records_, std::max<std::size_t>(16, 2 * records_.capacity()));
        records_.emplace_back();
        ++limit_;
      }
      return *std::construct_at(&records_[write_++], made);
    }
    // Otherwise the slot is one already read (its record copied out or kept, see keep()), and no
    // unread record lies there.
    return *std::construct_at(&records_[write_++], std::forward<Args>(args)...);
  }
  // Last step's record `previous` (next() a moment ago) kept as this step's next record: where the
  // walk writes into the very slot it read it from (a steady pile), nothing is copied.
  Record& keep(const Record& previous) {
    if (write_ < limit_ && &previous == &records_[write_]) {
      lastOverflowed_ = false;
      return records_[write_++];
    }
    return emplace(previous);
  }
  // Takes back the record emplace() made last (the record turned out not to be kept).
  void dropLast() {
    if (lastOverflowed_) {
      block_->overflow.pop_back();
    } else {
      --write_;
    }
  }
  // The slot `ahead` places after the next one written, if the array has it (for prefetching).
  const Record* slotAhead(std::size_t ahead) const {
    return write_ + ahead < limit_ ? &records_[write_ + ahead] : nullptr;
  }

  // After the walk over the whole array: it holds this step's records alone (last step's not read
  // are dropped). After a block's walk: the block knows how many of this step's records it holds in
  // place (the rest are in its overflow).
  void finish() {
    if (block_) {
      block_->inPlace = write_ - block_->begin;
    } else {
      records_.resize(write_);
    }
    // A landing (many new contacts ahead of the old ones) can spill tens of megabytes once; a
    // resting pile spills little or nothing.
    releaseOversizedScratch(spill_, mostSpilled_);
  }

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
    mostSpilled_ = std::max(mostSpilled_, spillCount_);
  }

  Array<Record>& records_;
  Array<Record>& spill_;
  MergeBlock<Record>* block_ = nullptr;  // a block's walk (its overflow); null: the array grows
  std::size_t readEnd_;                  // last step's records in the array are [read_, readEnd_)
  std::size_t read_ = 0;  // and those in the spill ring (spillCount_ from spillHead_) come first
  std::size_t spillHead_ = 0;
  std::size_t spillCount_ = 0;
  std::size_t mostSpilled_ = 0;  // this walk's most records in the spill ring at once
  std::size_t write_ = 0;        // this step's records are written from the block's begin (or 0) to here
  std::size_t limit_;            // writes in the array stop here
  bool lastOverflowed_ = false;
};

// After walks over consecutive blocks of `records`: the blocks' records made one array in block
// order. Blocks that move towards the front are moved first, front to back, then those that move
// towards the back, back to front: no block is written over before it has moved (each block's
// final place starts after every earlier block's final end, which is past that block's data).
template <typename Record>
void compactBlocks(Array<Record>& records, std::span<const MergeBlock<Record>> blocks) {
  const auto written = [](const MergeBlock<Record>& block) { return block.inPlace + block.overflow.size(); };
  std::size_t total = 0;
  for (const MergeBlock<Record>& block : blocks) total += written(block);
  if (total > records.size()) records.resize(total);
  const auto at = [&](std::size_t index) { return records.begin() + static_cast<std::ptrdiff_t>(index); };
  std::size_t offset = 0;
  for (const MergeBlock<Record>& block : blocks) {
    if (offset < block.begin) std::copy(at(block.begin), at(block.begin + block.inPlace), at(offset));
    offset += written(block);
  }
  for (std::size_t b = blocks.size(); b-- > 0;) {
    const MergeBlock<Record>& block = blocks[b];
    offset -= written(block);
    if (offset > block.begin)
      std::copy_backward(at(block.begin), at(block.begin + block.inPlace), at(offset + block.inPlace));
  }
  for (const MergeBlock<Record>& block : blocks) {
    std::copy(block.overflow.begin(), block.overflow.end(), at(offset + block.inPlace));
    offset += written(block);
  }
  records.resize(total);
}

}  // namespace collide::detail
