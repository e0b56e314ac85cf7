// The world step on a reduced R2 (sphere rain, docs/benchmarks.md): 1,000 spheres (10 x 10 x 10,
// radius 0.25, spacing 0.6, lowest layer at y = 1) falling into the open box container of R2, 60
// steps at 60 Hz. Every sphere is flagged for continuous collision; the world switch turns the
// time-of-impact pass on or off, so the ratio of the two runs is what ccd costs when bodies are
// mostly slow (docs/ccd.md: a body is "fast" only when it moves more than half its radius in a step).
#include <benchmark/benchmark.h>
#include <collide/world.h>

#include <memory>

using namespace collide;

namespace {

std::unique_ptr<World> makeRain(bool ccd, int perSide) {
  WorldDef def;
  def.ccd = ccd;
  auto world = std::make_unique<World>(def);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Shape(Box{Vec3(100.0f, 0.5f, 100.0f)});
  ground.position = Vec3(0.0f, -0.5f, 0.0f);
  world->createBody(ground);
  // Four walls 0.5 thick and 10 high enclosing x, z in [-7, 7].
  for (int i = 0; i < 4; ++i) {
    BodyDef wall;
    wall.type = BodyType::Static;
    const bool alongX = i < 2;
    const float sign = (i % 2 == 0) ? 1.0f : -1.0f;
    wall.shape = Shape(Box{alongX ? Vec3(7.5f, 5.0f, 0.25f) : Vec3(0.25f, 5.0f, 7.5f)});
    wall.position = alongX ? Vec3(0.0f, 5.0f, sign * 7.25f) : Vec3(sign * 7.25f, 5.0f, 0.0f);
    world->createBody(wall);
  }
  const float spacing = 0.6f;
  const float offset = 0.5f * spacing * static_cast<float>(perSide - 1);
  for (int x = 0; x < perSide; ++x) {
    for (int y = 0; y < perSide; ++y) {
      for (int z = 0; z < perSide; ++z) {
        BodyDef ball;
        ball.shape = Shape(Sphere{0.25f});
        ball.mass = 1.0f;
        ball.position = Vec3(spacing * x - offset, 1.0f + spacing * y, spacing * z - offset);
        ball.ccd = true;
        world->createBody(ball);
      }
    }
  }
  return world;
}

// state.range(0) steps: 40 steps end before any sphere reaches 7.5 m/s (half its radius per step,
// the "fast" threshold), so that run measures the pass's cost when no body is fast; by 60 steps the
// upper layers are fast and run time-of-impact queries against their neighbours.
void runRain(benchmark::State& state, bool ccd) {
  const auto steps = static_cast<int>(state.range(0));
  for (auto _ : state) {
    state.PauseTiming();
    std::unique_ptr<World> world = makeRain(ccd, 10);
    state.ResumeTiming();
    for (int i = 0; i < steps; ++i) world->step(1.0f / 60.0f);
    benchmark::DoNotOptimize(world->kineticEnergy());
  }
  state.counters["ms_per_step"] =
      benchmark::Counter(static_cast<double>(steps),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_RainCcdOff(benchmark::State& state) { runRain(state, false); }
void BM_RainCcdOn(benchmark::State& state) { runRain(state, true); }

}  // namespace

BENCHMARK(BM_RainCcdOff)->Arg(40)->Arg(60)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RainCcdOn)->Arg(40)->Arg(60)->Unit(benchmark::kMillisecond);
