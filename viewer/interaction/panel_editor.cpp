#include "hirsute/viewer/interaction/panel_editor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

#include "hirsute/core/model_folder.h"
#include "hirsute/core/output_target.h"

namespace hirsute {
namespace {

// The most panels read from one folder: each is a window.
constexpr std::size_t kMaxPanels = 16;

const DefineConstant* constantNamed(const std::vector<DefineConstant>& constants,
                                    const std::string& name) {
  for (const DefineConstant& c : constants) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

}  // namespace

PanelEditor::PanelEditor(std::filesystem::path modelFolder, std::string lsystemStem)
    : folder_(modelFolder.empty() ? "." : std::move(modelFolder)), stem_(std::move(lsystemStem)) {
  reload();
}

void PanelEditor::reload() {
  std::vector<std::filesystem::path> found;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder_, error)) {
    if (entry.path().extension() == ".pnl" && entry.path().filename().string()[0] != '.')
      found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  if (found.size() > kMaxPanels) found.resize(kMaxPanels);
  const std::filesystem::path lastPath =
      lastEdited_ && *lastEdited_ < panels_.size() ? panels_[*lastEdited_].path : "";
  std::vector<Panel> panels;
  const ModelFolder model(folder_);
  for (const std::filesystem::path& path : found) {
    auto kept = std::find_if(panels_.begin(), panels_.end(),
                             [&](const Panel& p) { return p.path == path; });
    if (kept != panels_.end() && kept->history.modified()) {
      panels.push_back(std::move(*kept));
      continue;
    }
    Panel panel;
    panel.path = path;
    if (kept != panels_.end()) panel.state = kept->state;
    std::string text, failure;
    const std::string name = path.filename().string();
    const bool read = model.read(name, text, failure, kMaxPanelBytes + 1);
    // A panel that still holds what the editor saved keeps its history and its controls.
    if (read && kept != panels_.end() && kept->error.empty() &&
        text == controlPanelText(kept->history.current())) {
      panels.push_back(std::move(*kept));
      continue;
    }
    if (!read) {
      panel.error = path.string() + ": cannot read the panel: " + failure;
    } else {
      try {
        panel.history = EditHistory<ControlPanel>(parseControlPanel(text, path.string()));
      } catch (const DiagnosticError& e) {
        panel.error = e.diagnostic().text();
      }
    }
    panels.push_back(std::move(panel));
  }
  // The panel edited last keeps its place in undo's reach when it is still there.
  std::optional<std::size_t> last;
  for (std::size_t p = 0; p < panels.size() && !lastPath.empty(); ++p) {
    if (panels[p].path == lastPath) last = p;
  }
  panels_ = std::move(panels);
  lastEdited_ = last;
}

int PanelEditor::shownValue(std::size_t panel, std::size_t item,
                            const std::vector<DefineConstant>& constants,
                            const std::map<std::string, std::string>& changed) const {
  const Panel& p = panels_.at(panel);
  const PanelItem& it = p.history.current().items.at(item);
  if (it.type == PanelItem::Type::Slider) {
    if (const auto message = defineMessage(it.message)) {
      if (const DefineConstant* c = constantNamed(constants, message->name)) {
        auto found = changed.find(c->name);
        const double value =
            found != changed.end() ? std::strtod(found->second.c_str(), nullptr) : c->value;
        return static_cast<int>(std::lround(value * message->scale));
      }
    }
  }
  auto state = p.state.find(item);
  if (state != p.state.end()) return state->second;
  if (it.type == PanelItem::Type::Button) return it.value == 1 ? 1 : 0;
  return it.value;
}

std::optional<std::pair<std::string, std::string>> PanelEditor::activate(
    std::size_t panel, std::size_t item, int value, const std::vector<DefineConstant>& constants) {
  Panel& p = panels_.at(panel);
  const ControlPanel& document = p.history.current();
  const PanelItem& it = document.items.at(item);
  if (it.type == PanelItem::Type::Slider) value = std::clamp(value, it.minimum, it.maximum);
  p.state[item] = value;
  // A button of a group turned on turns the group's others off (vlab §2.3: only the one turned
  // on sends its message).
  if (it.type == PanelItem::Type::Button && value == 1) {
    for (const PanelItem& group : document.items) {
      if (group.type != PanelItem::Type::Group) continue;
      if (std::find(group.buttons.begin(), group.buttons.end(), it.name) == group.buttons.end())
        continue;
      for (std::size_t b = 0; b < document.items.size(); ++b) {
        const PanelItem& other = document.items[b];
        if (b != item && other.type == PanelItem::Type::Button &&
            std::find(group.buttons.begin(), group.buttons.end(), other.name) !=
                group.buttons.end())
          p.state[b] = 0;
      }
    }
  }
  const auto message = defineMessage(it.message);
  if (!message) return std::nullopt;
  const DefineConstant* c = constantNamed(constants, message->name);
  return std::make_pair(message->name, defineValueFor(*message, value, c ? c->integer : true));
}

bool PanelEditor::edit(std::size_t panel, ControlPanel next) {
  Panel& p = panels_.at(panel);
  if (!p.error.empty()) return false;
  if (next == p.history.current()) return true;
  p.history.record(std::move(next));
  p.state.clear();  // the items may have moved
  lastEdited_ = panel;
  return true;
}

bool PanelEditor::undo(std::size_t panel) {
  if (panel >= panels_.size() || !panels_[panel].history.undo()) return false;
  panels_[panel].state.clear();
  return true;
}

bool PanelEditor::redo(std::size_t panel) {
  if (panel >= panels_.size() || !panels_[panel].history.redo()) return false;
  panels_[panel].state.clear();
  return true;
}

bool PanelEditor::modified() const {
  return std::any_of(panels_.begin(), panels_.end(),
                     [](const Panel& p) { return p.history.modified(); });
}

std::string PanelEditor::save(std::size_t panel) {
  Panel& p = panels_.at(panel);
  if (!p.error.empty()) return p.error;
  const std::string text = controlPanelText(p.history.current());
  try {
    OutputTarget out(OutputFolder(folder_), p.path.filename().string());
    if (std::fwrite(text.data(), 1, text.size(), out.stream()) != text.size())
      throw std::runtime_error(p.path.string() + ": cannot write the file");
    out.commit();
  } catch (const std::exception& e) {
    return e.what();
  }
  p.history.markSaved();
  return {};
}

std::string PanelEditor::create(const std::vector<DefineConstant>& constants,
                                std::size_t* created) {
  const std::string name = stem_ + ".pnl";
  const std::filesystem::path path = folder_ / name;
  std::error_code error;
  if (std::filesystem::exists(std::filesystem::symlink_status(path, error)))
    return path.string() + ": exists already; not replaced";
  if (constants.empty()) return "the .l has no #define constant of one number to make a panel of";
  if (panels_.size() >= kMaxPanels)
    return "the model's folder has " + std::to_string(kMaxPanels) + " panels already";
  Panel panel;
  panel.path = path;
  panel.history = EditHistory<ControlPanel>(makeControlPanel(constants, stem_, stem_ + ".l"));
  const std::string text = controlPanelText(panel.history.current());
  try {
    OutputTarget out(OutputFolder(folder_), name);
    if (std::fwrite(text.data(), 1, text.size(), out.stream()) != text.size())
      throw std::runtime_error(path.string() + ": cannot write the file");
    out.commit();
  } catch (const std::exception& e) {
    return e.what();
  }
  panels_.push_back(std::move(panel));
  if (created) *created = panels_.size() - 1;
  return {};
}

}  // namespace hirsute
