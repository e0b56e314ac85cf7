#include "world_settings_panel.h"

#include <imgui.h>

#include <string>

namespace collide::viewer {
namespace {

// A combo over an enumeration's values 0 .. count-1, labelled by the library's own names (the scene
// file's spelling), so the panel and the scene format never disagree.
template <typename Enum>
bool enumCombo(const char* label, Enum& value, int count) {
  bool changed = false;
  const std::string current(toString(value));
  if (ImGui::BeginCombo(label, current.c_str())) {
    for (int i = 0; i < count; ++i) {
      const Enum option = static_cast<Enum>(i);
      const std::string name(toString(option));
      if (ImGui::Selectable(name.c_str(), option == value)) {
        changed = option != value;
        value = option;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

// ImGui 1.86 (Debian's) has no SeparatorText.
void section(const char* title) {
  ImGui::Spacing();
  ImGui::TextDisabled("%s", title);
  ImGui::Separator();
}

bool positiveFloat(const char* label, float& value, float speed, float min, float max, const char* format) {
  return ImGui::DragFloat(label, &value, speed, min, max, format, ImGuiSliderFlags_AlwaysClamp);
}

}  // namespace

bool editWorldSettings(WorldDef& def, float& dt) {
  bool changed = false;
  ImGui::PushItemWidth(160.0f);
  changed |= ImGui::DragFloat3("gravity", &def.gravity.x, 0.05f, -100.0f, 100.0f, "%.2f");
  float hertz = 1.0f / dt;
  if (ImGui::DragFloat("steps per second", &hertz, 1.0f, 10.0f, 1000.0f, "%.0f",
                       ImGuiSliderFlags_AlwaysClamp)) {
    dt = 1.0f / hertz;
    changed = true;
  }
  changed |= ImGui::SliderInt("substeps", &def.substeps, 1, 32, "%d", ImGuiSliderFlags_AlwaysClamp);

  section("broad phase");
  changed |= enumCombo("type", def.broadPhase.type, kBroadPhaseTypeCount);
  if (def.broadPhase.type == BroadPhaseType::Tree)
    changed |= positiveFloat("tree margin (m)", def.broadPhase.treeMargin, 0.005f, 0.0f, 2.0f, "%.3f");
  if (def.broadPhase.type == BroadPhaseType::Grid) {
    changed |=
        positiveFloat("cell size (m, 0 auto)", def.broadPhase.gridCellSize, 0.01f, 0.0f, 50.0f, "%.2f");
    int cells = static_cast<int>(def.broadPhase.gridMaxCellsPerAxis);
    if (ImGui::SliderInt("max cells per axis", &cells, 1, 64, "%d", ImGuiSliderFlags_AlwaysClamp)) {
      def.broadPhase.gridMaxCellsPerAxis = static_cast<std::uint32_t>(cells);
      changed = true;
    }
  }

  section("response");
  // The value counts of world.h's enumerations.
  changed |= enumCombo("impact model", def.impactModel, 2);
  changed |= enumCombo("friction model", def.frictionModel, 4);
  changed |= enumCombo("bounciness combine", def.bouncinessCombine, 4);
  changed |= enumCombo("friction combine", def.frictionCombine, 4);
  changed |= enumCombo("penetration response", def.penetrationResponse, 3);
  changed |= ImGui::Checkbox("ccd (bodies flagged ccd)", &def.ccd);

  section("contact tuning");
  ContactTuning& c = def.contact;
  changed |= positiveFloat("hertz", c.hertz, 0.5f, 1.0f, 1000.0f, "%.1f");
  changed |= positiveFloat("damping ratio", c.dampingRatio, 0.01f, 0.0f, 50.0f, "%.2f");
  changed |= positiveFloat("push-out speed (m/s)", c.pushOutSpeed, 0.05f, 0.0f, 100.0f, "%.2f");
  changed |= positiveFloat("restitution threshold (m/s)", c.restitutionThreshold, 0.05f, 0.0f, 50.0f, "%.2f");
  changed |= positiveFloat("linear slop (m)", c.linearSlop, 0.0005f, 0.0f, 0.5f, "%.4f");
  changed |= positiveFloat("speculative distance (m)", c.speculativeDistance, 0.001f, 0.0f, 1.0f, "%.3f");
  if (ImGui::SliderInt("relax passes", &c.relaxPasses, 0, 4, "%d", ImGuiSliderFlags_AlwaysClamp))
    changed = true;
  changed |=
      positiveFloat("friction anchor reach (m, 0 off)", c.frictionAnchorReach, 0.001f, 0.0f, 1.0f, "%.3f");
  changed |= positiveFloat("manifold cache (m, 0 off)", c.manifoldCacheDistance, 0.0005f, 0.0f, 0.1f, "%.4f");
  changed |= ImGui::Checkbox("persist events", &def.persistEvents);

  section("sleeping");
  changed |= ImGui::Checkbox("resting islands sleep", &def.sleeping);
  if (def.sleeping) {
    changed |= positiveFloat("linear speed (m/s)", def.sleep.linearSpeed, 0.005f, 0.0f, 10.0f, "%.3f");
    changed |= positiveFloat("angular speed (rad/s)", def.sleep.angularSpeed, 0.005f, 0.0f, 10.0f, "%.3f");
    changed |= positiveFloat("time to sleep (s)", def.sleep.timeToSleep, 0.05f, 0.0f, 30.0f, "%.2f");
  }
  ImGui::PopItemWidth();
  return changed;
}

}  // namespace collide::viewer
