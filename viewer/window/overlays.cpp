#include "hirsute/viewer/window/overlays.h"

#include <imgui.h>

#include <algorithm>
#include <span>

#include "hirsute/hairs/organ_stage.h"
#include "hirsute/viewer/interaction/live_organ.h"
#include "hirsute/viewer/window/key_map.h"

namespace hirsute {
namespace {

constexpr ImGuiWindowFlags kOverlay =
    ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
    ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
    ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove;

}  // namespace

void drawStatusOverlay(const LiveModel& live, const GlRenderer& renderer,
                       const std::string& modelName, double frameMs, bool thinned) {
  const ImVec2 size = ImGui::GetMainViewport()->WorkSize;
  const ViewerModel* model = live.model();
  const ShownParts& shown = live.shown();
  ImGui::SetNextWindowPos(ImVec2(8, size.y - 8), ImGuiCond_Always, ImVec2(0, 1));
  ImGui::SetNextWindowBgAlpha(0.55f);
  if (ImGui::Begin("##status", nullptr, kOverlay)) {
    ImGui::Text("%s  step %d / %d%s   %.1f ms   F1: help", modelName.c_str(),
                model ? model->steps : 0, live.derivationLength(),
                live.animating() ? "  (animating)" : "", frameMs);
    // A line per organ drawn: its name, its count and its own words (live_organ.h).
    const std::span<const LiveOrganType* const> organs = liveOrgans();
    for (std::size_t k = 0; model && k < organs.size(); ++k) {
      const char* name = organs[k]->name();
      const std::size_t count = renderer.organInstances(name);
      if (count == 0) continue;
      ImGui::Text("%s %zu%s%s", name, count, shown.organShown(name) ? "" : " (hidden)",
                  thinned && renderer.organThins(name) ? "  (fewer while moving)" : "");
      const std::string status = live.organ(k).status();
      if (!status.empty()) ImGui::Text("  %s", status.c_str());
    }
    // Builds that end within a quarter of a second show no progress (no flicker).
    const ModelWorker& worker = live.worker();
    if (worker.busy() && worker.runningSeconds() > 0.25) {
      const BuildProgress& p = worker.progress();
      // Past interpretation, the organs' stages in their order (organ_stage.h).
      static const char* kPhases[] = {"reading", "deriving", "interpreting"};
      const std::span<const OrganStage* const> stages = organStages();
      const int phase = std::clamp(p.phase.load(), 0, 2 + static_cast<int>(stages.size()));
      const char* activity =
          phase < 3 ? kPhases[phase] : stages[static_cast<std::size_t>(phase - 3)]->activity();
      if (p.totalSteps > 0 && phase == 1) {
        ImGui::Text("%s: step %d of %d  %.1f s", activity, p.stepsDone.load(),
                    p.totalSteps.load(), worker.runningSeconds());
        ImGui::ProgressBar(static_cast<float>(p.stepsDone) / static_cast<float>(p.totalSteps),
                           ImVec2(240, 0));
      } else {
        ImGui::Text("%s...  %.1f s", activity, worker.runningSeconds());
      }
    }
  }
  ImGui::End();
}

void drawErrorOverlay(const std::string& error) {
  if (error.empty()) return;
  const ImVec2 size = ImGui::GetMainViewport()->WorkSize;
  ImGui::SetNextWindowPos(ImVec2(size.x - 8, 8), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(size.x * 0.7f, size.y * 0.5f));
  if (ImGui::Begin("##error", nullptr, kOverlay)) {
    ImGui::PushTextWrapPos(size.x * 0.65f);
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", error.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
}

void drawHelpOverlay(bool* open) {
  if (!*open) return;
  const ImVec2 size = ImGui::GetMainViewport()->WorkSize;
  ImGui::SetNextWindowPos(ImVec2(size.x / 2, size.y / 2), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (ImGui::Begin("Keys and mouse", open,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                       ImGuiWindowFlags_NoCollapse)) {
    if (ImGui::BeginTable("keys", 2)) {
      for (const auto& [key, action] : viewerKeyMap()) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(key.c_str());
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(action.c_str());
      }
      ImGui::EndTable();
    }
  }
  ImGui::End();
}

}  // namespace hirsute
