// Running the step on several cores: the task interface an engine implements with its own job
// system, or the thread pool collide starts when the engine gives none (WorldDef::workerCount).
// Box2D v3's enqueueTask / finishTask callbacks are the model.
//
// The step hands its parallel stages to the task system as tasks over ranges of items (batches of
// contacts of one colour, bodies to integrate). Each item's work depends on nothing another item of
// the same task writes, so the result is bit-identical whichever worker runs which range, however
// the items are split, and with any number of workers.
#pragma once

#include <cstdint>

namespace collide {

// A task's work on items [begin, end), run by worker `worker`: 0 .. workerCount - 1, and no two
// ranges running at the same time may have the same worker index (a worker may keep scratch).
using TaskFunction = void(std::uint32_t begin, std::uint32_t end, std::uint32_t worker, void* taskContext);

// Starts `task` over items [0, itemCount): the engine splits them into ranges of at least
// `minRange` items (the last may be shorter) and has its workers call task(begin, end, worker,
// taskContext) once per range, each item in exactly one range. Returns a handle that finishTask
// waits on, or nullptr after running every range on the calling thread.
using EnqueueTaskCallback = void*(TaskFunction* task, std::uint32_t itemCount, std::uint32_t minRange,
                                  void* taskContext, void* userContext);
// Returns once every range of the task behind `userTask` (enqueueTask's handle) has run.
using FinishTaskCallback = void(void* userTask, void* userContext);

// The workers a world steps with (WorldDef::workerCount, at most kMaxWorkers).
inline constexpr int kMaxWorkers = 64;

}  // namespace collide
