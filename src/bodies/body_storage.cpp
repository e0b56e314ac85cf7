// The body storage's slots: allocation with generations, freeing, forces cleared (body_storage.h).
#include "bodies/body_storage.h"
#include "base/fail.h"

#include <collide/error.h>

#include <string>

#include "memory/heap_bytes.h"

namespace collide::detail {

std::uint32_t BodyStorage::allocate() {
  std::uint32_t index;
  if (!freeSlots_.empty()) {
    index = freeSlots_.back();
    freeSlots_.pop_back();
  } else {
    index = static_cast<std::uint32_t>(records.size());
    records.emplace_back();
    states.emplace_back();
  }
  const std::uint32_t generation = records[index].generation;
  records[index] = BodyRecord{};
  records[index].generation = generation;
  records[index].alive = true;
  states[index] = BodyState{};
  ++aliveCount;
  return index;
}

void BodyStorage::free(std::uint32_t index) {
  BodyRecord& record = records[index];
  record.alive = false;
  record.shape = Shape(Sphere{});  // release shared polyhedra now
  ++record.generation;             // stale ids to this slot are detected from now on
  states[index] = BodyState{};
  freeSlots_.push_back(index);
  --aliveCount;
}

void BodyStorage::clearForces() {
  for (BodyRecord& r : records) {
    r.force = Vec3(0.0f);
    r.torque = Vec3(0.0f);
  }
}

std::size_t BodyStorage::memoryBytes() const {
  std::size_t bytes = heapBytes(records) + heapBytes(states) + heapBytes(freeSlots_);
  for (const BodyRecord& record : records) bytes += heapBytes(record.parts) + heapBytes(record.name);
  return bytes;
}

void BodyStorage::restore(Array<BodyRecord> restoredRecords, Array<BodyState> restoredStates,
                          Array<std::uint32_t> restoredFreeSlots) {
  if (restoredRecords.size() != restoredStates.size())
    COLLIDE_FAIL("bodies: " + std::to_string(restoredRecords.size()) + " records but " +
                 std::to_string(restoredStates.size()) + " states");
  Array<std::uint8_t> free(restoredRecords.size(), 0);
  for (const std::uint32_t slot : restoredFreeSlots) {
    if (slot >= restoredRecords.size() || restoredRecords[slot].alive || free[slot])
      COLLIDE_FAIL("bodies: free slot " + std::to_string(slot) + " is out of range, alive or listed twice");
    free[slot] = 1;
  }
  records = std::move(restoredRecords);
  states = std::move(restoredStates);
  freeSlots_ = std::move(restoredFreeSlots);
  aliveCount = bouncyCount = rollingCount = sensorCount = 0;
  for (const BodyRecord& record : records) {
    if (!record.alive) continue;
    ++aliveCount;
    tally(record, +1);
  }
}

}  // namespace collide::detail
