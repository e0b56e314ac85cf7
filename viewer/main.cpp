// collide-viewer [SCENE]: the interactive testbed. Shows a scene (a built-in name or a scene file,
// as `collide run` takes) stepping live, with a panel to pause, step, restart and switch scenes,
// edit every world setting, draw the broad phase, and the step's timing and pair counters; the
// mouse drags bodies and shoots spheres. `--replay FILE` plays a recording of the scene (`collide
// run --record`) instead, with a timeline: play, pause, step, scrub, speed. `--screenshot FILE
// --frames N` renders N steps (or the recording's frame of step N) into a hidden window and writes a
// PNG, which is how the viewer is tested headless (under xvfb-run).
#include "camera_report.h"
#include "gl.h"
#include "interaction.h"
#include "orbit_camera.h"
#include "renderer.h"
#include "viewer_scene.h"
#include "world_settings_panel.h"

#include <collide/error.h>
#include <collide/scene/builtin_scenes.h>
#include <collide/scene/recording.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <stb_image_write.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

using namespace collide;
using namespace collide::viewer;

namespace {

constexpr Vec3 kBackground(0.16f, 0.18f, 0.21f);

struct Options {
  std::string scene = "proxies";
  std::string screenshot;  // empty: interactive
  std::string cameraJson;  // with --screenshot: the camera and the bodies, for the pixel test
  std::string broadPhase;  // empty: the scene's
  std::string replay;      // a recording of the scene to play instead of stepping
  int frames = 120;
  int width = 1280;
  int height = 720;
  bool noUi = false;
  DebugLines debug;
};

// The same rule as `collide run`: an existing file or something path-like is a scene file,
// anything else a built-in name (whose error lists the built-ins).
scene::Scene loadSceneArgument(const std::string& argument) {
  const std::filesystem::path path(argument);
  const bool pathLike = path.has_parent_path() || path.has_extension();
  return std::filesystem::exists(path) || pathLike ? scene::loadSceneFile(path)
                                                   : scene::loadBuiltinScene(argument);
}

// The state the panel shows and changes.
struct App {
  Options options;
  GLFWwindow* window = nullptr;
  std::unique_ptr<Renderer> renderer;
  std::unique_ptr<ViewerScene> scene;
  std::string sceneName;
  OrbitCamera camera;
  bool playing = true;
  bool stepOnce = false;
  double stepMs = 0.0;  // smoothed
  double lastStepMs = 0.0;
  std::string error;  // the last scene or settings the World refused, shown in the panel

  // The settings edited in the panel, applied to the running World as they change.
  WorldDef settings;
  float dt = 1.0f / 60.0f;
  bool settingsEdited = false;  // differ from the running World's (the World refused them)

  // Replay: the recording, the frame shown, and the timeline's state. The clock counts recorded
  // frames; at speed 1 one frame is shown per drawn frame, as live stepping takes one step.
  std::optional<scene::Recording> recording;
  int replayFrame = 0;
  double replayClock = 0.0;
  float replaySpeed = 1.0f;
  bool replayLoop = true;
  std::size_t replayUnknownBodies = 0;

  MouseSpring spring;
  SphereShot shot;
  enum class MouseMode { None, Orbit, Drag };
  MouseMode mouseMode = MouseMode::None;
  bool leftWasDown = false;
  int shotsRequested = 0;  // space presses since the last frame (a callback: a tap is shorter than a frame)

  // Player: WASD walks the scene's first character relative to the camera, space jumps, and the
  // camera follows it.
  bool drivePlayer = false;
  float walkSpeed = 4.0f;  // m/s
  float jumpSpeed = 5.0f;  // m/s
  bool jumpRequested = false;
  double lastX = 0.0, lastY = 0.0;

  // Loads the scene and builds its World (with the edited settings when `keepSettings`). Builds
  // first, so that a scene or settings the World refuses leave the current scene running.
  void load(const std::string& name, bool reframe, bool keepSettings) {
    scene::Scene loaded = loadSceneArgument(name);
    if (keepSettings) {
      loaded.world = settings;
      loaded.dt = dt;
    } else if (!options.broadPhase.empty()) {
      loaded.world.broadPhase.type = parseBroadPhaseType(options.broadPhase);
    }
    scene::SceneWorld built = scene::buildWorld(loaded);
    spring.forget();  // its bodies belong to the World being replaced
    mouseMode = MouseMode::None;
    scene.reset();
    renderer->clearMeshes();
    scene = std::make_unique<ViewerScene>(std::move(loaded), std::move(built), *renderer);
    sceneName = name;
    settings = scene->scene().world;
    dt = scene->scene().dt;
    settingsEdited = false;
    stepMs = lastStepMs = 0.0;
    if (reframe) camera.frame(scene->bounds());
  }

  void tryLoad(const std::string& name, bool reframe, bool keepSettings) {
    try {
      load(name, reframe, keepSettings);
      error.clear();
    } catch (const Error& e) {
      error = e.what();
    }
  }

  void step() {
    if (recording) {
      advanceReplay(1.0);
      return;
    }
    lastStepMs = scene->step();
    stepMs = scene->stepCount() == 1 ? lastStepMs : 0.9 * stepMs + 0.1 * lastStepMs;
  }

  void startReplay(scene::Recording replay) {
    if (replay.frames.empty()) throw Error("viewer: the recording has no frames");
    recording = std::move(replay);
    replayClock = 0.0;
    showFrame(0);
  }

  void showFrame(int index) {
    const int last = static_cast<int>(recording->frames.size()) - 1;
    replayFrame = std::clamp(index, 0, last);
    replayUnknownBodies = scene->showRecordedFrame(recording->frames[static_cast<std::size_t>(replayFrame)]);
  }

  // The frame whose step is the last one at or before `step` (the recording may skip steps: --every).
  int frameOfStep(int step) const {
    const auto& frames = recording->frames;
    const auto after = std::upper_bound(frames.begin(), frames.end(), step,
                                        [](int s, const scene::RecordedFrame& f) { return s < f.step; });
    return after == frames.begin() ? 0 : static_cast<int>(after - frames.begin()) - 1;
  }

  // Playing: `frames` drawn frames' worth of the recording at the chosen speed.
  void advanceReplay(double frames) {
    replayClock += frames * replaySpeed;
    int next = replayFrame;
    while (replayClock >= 1.0) {
      replayClock -= 1.0;
      ++next;
    }
    const int count = static_cast<int>(recording->frames.size());
    if (next >= count) {
      if (replayLoop) {
        next %= count;
      } else {
        next = count - 1;
        playing = false;
      }
    }
    if (next != replayFrame) showFrame(next);
  }

  void replayPanel() {
    const scene::RecordedFrame& frame = recording->frames[static_cast<std::size_t>(replayFrame)];
    ImGui::Separator();
    ImGui::Text("replay: frame %d of %zu (step %d, t = %.2f s)", replayFrame + 1, recording->frames.size(),
                frame.step, frame.time);
    if (ImGui::Button(playing ? "Pause" : "Play")) playing = !playing;
    ImGui::SameLine();
    if (ImGui::Button("<")) {
      playing = false;
      showFrame(replayFrame - 1);
    }
    ImGui::SameLine();
    if (ImGui::Button(">")) {
      playing = false;
      showFrame(replayFrame + 1);
    }
    ImGui::SameLine();
    ImGui::Checkbox("loop", &replayLoop);
    ImGui::SetNextItemWidth(300.0f);
    int scrub = replayFrame;
    if (ImGui::SliderInt("frame", &scrub, 0, static_cast<int>(recording->frames.size()) - 1))
      showFrame(scrub);
    ImGui::SetNextItemWidth(300.0f);
    ImGui::SliderFloat("speed", &replaySpeed, 0.125f, 8.0f, "%.3gx", ImGuiSliderFlags_Logarithmic);
    if (replayUnknownBodies > 0) {
      ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "%zu bodies of the recording are not in this scene",
                         replayUnknownBodies);
    }
    if (ImGui::Button("Back to the live scene")) {
      recording.reset();
      tryLoad(sceneName, false, true);
    }
  }

  Ray cursorRay() const {
    int width = 0, height = 0;
    glfwGetWindowSize(window, &width, &height);
    return camera.rayThrough(float(lastX), float(lastY), float(width), float(height));
  }

  void panel() {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    // As wide as its widgets, at most as tall as the window (it scrolls then).
    ImGui::SetNextWindowSizeConstraints(ImVec2(300, 0), ImVec2(600, ImGui::GetIO().DisplaySize.y - 20));
    ImGui::Begin("collide", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::SetNextItemWidth(200.0f);
    if (ImGui::BeginCombo("scene", sceneName.c_str())) {
      for (const scene::BuiltinScene& builtin : scene::builtinScenes()) {
        const std::string name(builtin.name);
        if (ImGui::Selectable(name.c_str(), name == sceneName)) {
          recording.reset();  // a recording belongs to its scene
          tryLoad(name, true, false);
        }
        if (ImGui::IsItemHovered()) {
          ImGui::SetTooltip("%.*s", int(builtin.description.size()), builtin.description.data());
        }
      }
      ImGui::EndCombo();
    }
    if (recording) {
      replayPanel();
    } else {
      if (ImGui::Button(playing ? "Pause" : "Play")) playing = !playing;
      ImGui::SameLine();
      if (ImGui::Button("Step")) stepOnce = true;
      ImGui::SameLine();
      if (ImGui::Button("Restart")) tryLoad(sceneName, false, true);
    }
    if (!error.empty()) {
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 340.0f);
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error.c_str());
      ImGui::PopTextWrapPos();
    }
    if (!recording) statistics();
    if (ImGui::CollapsingHeader("Debug drawing", ImGuiTreeNodeFlags_DefaultOpen)) debugDrawing();
    if (!recording && ImGui::CollapsingHeader("Mouse and shots", ImGuiTreeNodeFlags_DefaultOpen))
      mouseAndShots();
    if (!recording && !scene->characters().empty() &&
        ImGui::CollapsingHeader("Player", ImGuiTreeNodeFlags_DefaultOpen))
      playerPanel();
    if (!recording && ImGui::CollapsingHeader("World settings")) worldSettings();
    ImGui::End();
  }

  void statistics() {
    const World& world = scene->world();
    ImGui::Separator();
    ImGui::Text("step %d  (t = %.2f s, dt = %.4f s)", scene->stepCount(),
                scene->stepCount() * scene->scene().dt, scene->scene().dt);
    ImGui::Text("%.3f ms per step (last %.3f)", stepMs, lastStepMs);
    ImGui::Text("bodies %zu   touching pairs %zu", world.bodyCount(), world.touchingContactCount());
    ImGui::Text("broad phase: %s", std::string(toString(world.def().broadPhase.type)).c_str());
    const StepStats& stats = world.lastStats();
    if (ImGui::BeginTable("stats", 2)) {
      const auto row = [](const char* label, unsigned long long value) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(label);
        ImGui::TableNextColumn();
        ImGui::Text("%llu", value);
      };
      row("proxies", stats.proxies);
      row("potential pairs", stats.potentialPairs);
      row("box tests", stats.boxTests);
      row("kept pairs", stats.keptPairs);
      row("narrow-phase tests", stats.narrowPhaseTests);
      row("contact pairs", stats.contactPairs);
      ImGui::EndTable();
    }
    // The last step's time by stage (it varies frame to frame; the state does not).
    if (ImGui::BeginTable("stage times", 2)) {
      const auto stage = [](const char* label, double seconds) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(label);
        ImGui::TableNextColumn();
        ImGui::Text("%.3f ms", seconds * 1e3);
      };
      const StageTimes& time = stats.time;
      for (const StageTimes::Stage& entry : StageTimes::kStages) stage(entry.label, time.*entry.seconds);
      stage("step", time.total());
      ImGui::EndTable();
    }
  }

  void debugDrawing() {
    DebugLines& debug = options.debug;
    ImGui::Checkbox("contact points and normals", &debug.contacts);
    ImGui::Checkbox("joints: anchors, axes, limits", &debug.joints);
    ImGui::Checkbox("bounding boxes", &debug.aabbs);
    ImGui::Checkbox("pairs the broad phase kept", &debug.pairs);
    const BroadPhaseType type = scene->world().def().broadPhase.type;
    if (type == BroadPhaseType::Tree) {
      ImGui::Checkbox("broad-phase tree", &debug.broadPhaseNodes);
      if (debug.broadPhaseNodes) {
        const int deepest = scene->broadPhaseDepth();
        ImGui::SameLine();
        ImGui::Checkbox("static tree too", &debug.staticTree);
        ImGui::SetNextItemWidth(200.0f);
        ImGui::DragIntRange2("depths", &debug.firstDepth, &debug.lastDepth, 0.1f, 0, deepest, "from %d",
                             "to %d");
        ImGui::TextDisabled("root 0, deepest %d; colour by depth", deepest);
      }
    } else if (type == BroadPhaseType::Grid) {
      ImGui::Checkbox("broad-phase grid cells", &debug.broadPhaseNodes);
    } else {
      ImGui::TextDisabled("(%s keeps no boxes of its own to draw)", std::string(toString(type)).c_str());
    }
  }

  void mouseAndShots() {
    ImGui::TextDisabled("left drag on a body: pull it; elsewhere: orbit");
    ImGui::TextDisabled("right drag: pan; wheel: zoom");
    ImGui::TextDisabled("space: shoot a sphere at the cursor");
    ImGui::PushItemWidth(160.0f);
    ImGui::SliderFloat("spring hertz", &spring.hertz, 0.5f, 20.0f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("spring damping", &spring.dampingRatio, 0.0f, 2.0f, "%.2f",
                       ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("shot speed (m/s)", &shot.speed, 1.0f, 500.0f, "%.0f",
                       ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("shot radius (m)", &shot.radius, 0.02f, 1.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("shot spin (rad/s)", &shot.spin, 0.0f, 500.0f, "%.0f", ImGuiSliderFlags_AlwaysClamp);
    ImGui::PopItemWidth();
    ImGui::Checkbox("shot ccd", &shot.ccd);
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "BodyDef::ccd on the shot. Speculative contacts alone stop straight shots;\n"
          "small fast spinning ones tunnel without ccd (docs/ccd.md; the tunneling scene).");
    }
    if (shot.ccd && !scene->world().def().ccd) {
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "(the world's ccd is off)");
    }
    if (ImGui::Button("Shoot at the centre")) {
      scene->shoot(Ray{camera.eye(), camera.forward(), 1e30f}, shot);
    }
    ImGui::SameLine();
    ImGui::Text("%zu shots (at most %zu)", scene->shotCount(), ViewerScene::kMaxShots);
  }

  void playerPanel() {
    ImGui::Checkbox("drive the first character", &drivePlayer);
    ImGui::TextDisabled(drivePlayer ? "WASD: walk (from the camera's view); space: jump"
                                    : "the characters walk their paths");
    ImGui::PushItemWidth(160.0f);
    ImGui::SliderFloat("walk speed (m/s)", &walkSpeed, 0.5f, 12.0f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
    ImGui::SliderFloat("jump speed (m/s)", &jumpSpeed, 0.0f, 15.0f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
    ImGui::PopItemWidth();
    const Character& player = scene->characters().front();
    const Vec3 feet = player.footPosition();
    ImGui::Text("feet (%.2f, %.2f, %.2f)  %s", feet.x, feet.y, feet.z,
                std::string(toString(player.groundState())).c_str());
  }

  // The walk the keys ask for: WASD in the camera's horizontal frame, space (this frame) a jump.
  void drivePlayerInput() {
    if (!drivePlayer || recording || scene->characters().empty()) {
      scene->drive(std::nullopt);
      jumpRequested = false;
      return;
    }
    const Character& player = scene->characters().front();
    const Vec3 up = player.def().up;
    Vec3 ahead = camera.forward() - glm::dot(camera.forward(), up) * up;
    ahead = glm::length(ahead) > 1e-4f ? glm::normalize(ahead) : Vec3(0.0f, 0.0f, -1.0f);
    const Vec3 right = glm::cross(ahead, up);
    Vec3 walk(0.0f);
    if (!ImGui::GetIO().WantCaptureKeyboard) {
      const auto held = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0f : 0.0f; };
      walk = (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * ahead + (held(GLFW_KEY_D) - held(GLFW_KEY_A)) * right;
      if (glm::length(walk) > 0.0f) walk = glm::normalize(walk) * walkSpeed;
    }
    if (jumpRequested && player.isOnGround()) walk += jumpSpeed * up;
    jumpRequested = false;
    scene->drive(walk);
    camera.target = player.position();
  }

  void worldSettings() {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 340.0f);
    ImGui::TextDisabled(
        "Each change applies from the next step (World::setDef). Restart rebuilds the scene with "
        "these settings.");
    ImGui::PopTextWrapPos();
    if (editWorldSettings(settings, dt)) {
      try {
        scene->applySettings(settings, dt);
        settingsEdited = false;
        error.clear();
      } catch (const Error& e) {
        settingsEdited = true;  // the World runs on with its last settings
        error = e.what();
      }
    }
    if (ImGui::Button(settingsEdited ? "Restart with these *" : "Restart with these"))
      tryLoad(sceneName, false, true);
    ImGui::SameLine();
    if (ImGui::Button("The scene's settings")) {
      tryLoad(sceneName, false, false);
    }
  }

  // Left drag: on a dynamic body it pulls the body (MouseSpring), elsewhere it orbits. Space shoots.
  void handleInput() {
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    const float dx = float(x - lastX), dy = float(y - lastY);
    lastX = x;
    lastY = y;
    const ImGuiIO& io = ImGui::GetIO();
    int width = 0, height = 0;
    glfwGetWindowSize(window, &width, &height);
    World& world = scene->world();

    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    if (left && !leftWasDown && !io.WantCaptureMouse) {
      // A replay only shows: the mouse orbits, it does not pull bodies.
      mouseMode = !recording && spring.grab(world, cursorRay(), camera.forward()) ? MouseMode::Drag
                                                                                  : MouseMode::Orbit;
    }
    if (!left && leftWasDown) {
      if (mouseMode == MouseMode::Drag) spring.release(world);
      mouseMode = MouseMode::None;
    }
    leftWasDown = left;
    if (mouseMode == MouseMode::Orbit) camera.orbit(dx, dy);
    if (mouseMode == MouseMode::Drag) {
      spring.drag(world, cursorRay(), camera.forward());
      if (!spring.active()) mouseMode = MouseMode::None;  // the body went away
    }
    if (!io.WantCaptureMouse && (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                                 glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS)) {
      camera.pan(dx, dy, float(height));
    }

    for (; shotsRequested > 0; --shotsRequested) {
      if (recording) {
        playing = !playing;  // space: play and pause the replay
      } else if (drivePlayer && !scene->characters().empty()) {
        jumpRequested = true;  // space: the player jumps
      } else {
        scene->shoot(cursorRay(), shot);
      }
    }
  }

  void render(int width, int height, bool ui) {
    glViewport(0, 0, width, height);
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const glm::mat4 viewProjection =
        camera.projection(float(width) / float(std::max(height, 1))) * camera.view();
    const Vec3 light = glm::normalize(Vec3(-0.35f, -1.0f, -0.55f));
    renderer->drawMeshes(scene->instances(renderer->meshCount()), viewProjection, light);
    std::vector<LineVertex> lines = scene->debugLines(options.debug);
    if (spring.active()) {
      // The spring: from the grabbed point to the cursor's point, white.
      const Vec3 white(1.0f);
      lines.push_back({spring.grabbedPoint(scene->world()), white});
      lines.push_back({spring.target(), white});
    }
    renderer->drawLines(lines, viewProjection);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (ui) panel();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }
};

void scrollCallback(GLFWwindow* window, double dx, double dy) {
  ImGui_ImplGlfw_ScrollCallback(window, dx, dy);
  if (ImGui::GetIO().WantCaptureMouse) return;
  static_cast<App*>(glfwGetWindowUserPointer(window))->camera.zoom(float(dy));
}

void keyCallback(GLFWwindow* window, int key, int scancode, int action, int mods) {
  ImGui_ImplGlfw_KeyCallback(window, key, scancode, action, mods);
  if (key != GLFW_KEY_SPACE || action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  ++static_cast<App*>(glfwGetWindowUserPointer(window))->shotsRequested;
}

// Renders into an offscreen framebuffer of the requested size (a hidden window's own buffer is
// not guaranteed to be kept), then reads it back bottom-up and writes it top-down.
void writeScreenshot(App& app) {
  const int width = app.options.width, height = app.options.height;
  GLuint framebuffer = 0, colour = 0, depth = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw Error("viewer: the offscreen framebuffer is incomplete");
  }
  // The panel needs a frame to measure itself before it is drawn in place.
  if (app.recording) {
    app.showFrame(app.frameOfStep(app.options.frames));
    app.render(width, height, !app.options.noUi);
  } else {
    for (int frame = 0; frame < app.options.frames; ++frame) {
      app.step();
      app.render(width, height, !app.options.noUi);
    }
  }
  if (app.options.frames == 0) app.render(width, height, !app.options.noUi);
  app.render(width, height, !app.options.noUi);
  std::vector<unsigned char> pixels(std::size_t(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteRenderbuffers(1, &depth);
  glDeleteRenderbuffers(1, &colour);
  glDeleteFramebuffers(1, &framebuffer);
  stbi_flip_vertically_on_write(1);
  if (!stbi_write_png(app.options.screenshot.c_str(), width, height, 3, pixels.data(), width * 3)) {
    throw Error("viewer: screenshot " + app.options.screenshot + ": cannot be written");
  }
  std::printf("%s: %dx%d, scene %s after %d steps\n", app.options.screenshot.c_str(), width, height,
              app.sceneName.c_str(), app.scene->stepCount());
  if (!app.options.cameraJson.empty()) {
    writeCameraReport(app.options.cameraJson, app.camera, width, height, kBackground, *app.scene);
  }
}

int run(const Options& options) {
  // The scene and the recording first: a bad name or file is reported without needing a display.
  (void)loadSceneArgument(options.scene);
  std::optional<scene::Recording> replay;
  if (!options.replay.empty()) replay = scene::loadRecording(options.replay);
  if (!options.broadPhase.empty()) (void)parseBroadPhaseType(options.broadPhase);
  glfwSetErrorCallback(
      [](int code, const char* text) { std::fprintf(stderr, "GLFW error %d: %s\n", code, text); });
  if (!glfwInit()) throw Error("viewer: GLFW cannot start (no display? run under xvfb-run -a)");
  struct GlfwGuard {
    ~GlfwGuard() { glfwTerminate(); }
  } glfwGuard;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  const bool headless = !options.screenshot.empty();
  if (headless) glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
  if (!headless) glfwWindowHint(GLFW_SAMPLES, 4);
  App app;
  app.options = options;
  app.window = glfwCreateWindow(options.width, options.height, "collide viewer", nullptr, nullptr);
  if (!app.window) throw Error("viewer: cannot open an OpenGL 3.3 core window");
  glfwMakeContextCurrent(app.window);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(app.window, &app);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(app.window, true);
  glfwSetScrollCallback(app.window, scrollCallback);  // both chain to ImGui's
  glfwSetKeyCallback(app.window, keyCallback);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  const auto shutdown = [&] {
    app.scene.reset();
    app.renderer.reset();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(app.window);
  };
  try {
    app.renderer = std::make_unique<Renderer>();
    app.load(options.scene, true, false);
    if (replay) app.startReplay(std::move(*replay));
    if (headless) {
      writeScreenshot(app);
    } else {
      glEnable(GL_MULTISAMPLE);
      while (!glfwWindowShouldClose(app.window)) {
        glfwPollEvents();
        app.handleInput();
        app.drivePlayerInput();
        if (app.playing || app.stepOnce) app.step();
        app.stepOnce = false;
        int width = 0, height = 0;
        glfwGetFramebufferSize(app.window, &width, &height);
        app.render(width, height, !app.options.noUi);
        glfwSwapBuffers(app.window);
      }
    }
  } catch (...) {
    shutdown();
    throw;
  }
  shutdown();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App cli{"collide-viewer: an interactive testbed for collide scenes"};
  cli.add_option("scene", options.scene, "a built-in scene (collide scenes lists them) or a scene file")
      ->capture_default_str();
  cli.add_option("--screenshot", options.screenshot, "render headless and write this PNG, then exit");
  cli.add_option(
      "--replay", options.replay,
      "play this recording of the scene (collide run --record) with a timeline instead of stepping");
  cli.add_option("--frames", options.frames, "steps before the screenshot (with --replay: the step shown)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cli.add_option("--width", options.width, "window or image width")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  cli.add_option("--height", options.height, "window or image height")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  cli.add_option("--camera-json", options.cameraJson,
                 "with --screenshot: also write the camera and every body's centre, size and colour as JSON")
      ->needs(cli.get_option("--screenshot"));
  cli.add_option("--broad-phase", options.broadPhase,
                 "override the scene's broad phase: tree, sap, grid, brute");
  cli.add_flag("--no-ui", options.noUi, "hide the panel");
  cli.add_flag("--contacts", options.debug.contacts, "draw contact points and normals");
  cli.add_flag("--aabbs", options.debug.aabbs, "draw the bodies' bounding boxes");
  cli.add_flag("--tree", options.debug.broadPhaseNodes, "draw the broad phase's tree nodes (or grid cells)");
  std::pair<int, int> depths{options.debug.firstDepth, options.debug.lastDepth};
  cli.add_option("--depths", depths, "with --tree: the first and last tree depth drawn (root 0)")
      ->check(CLI::NonNegativeNumber);
  cli.add_flag("--pairs", options.debug.pairs, "draw the pairs the broad phase kept");
  bool noJoints = false;
  cli.add_flag("--no-joints", noJoints, "start without the joints' anchors, axes and limits drawn");
  CLI11_PARSE(cli, argc, argv);
  options.debug.joints = !noJoints;
  options.debug.firstDepth = depths.first;
  options.debug.lastDepth = depths.second;
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "collide-viewer: %s\n", e.what());
    return 1;
  }
}
