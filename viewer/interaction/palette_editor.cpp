#include "hirsute/viewer/interaction/palette_editor.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <system_error>

#include "hirsute/core/model_folder.h"
#include "hirsute/core/output_target.h"

namespace hirsute {
namespace {

constexpr int kColorsPerBank = 256;

// The file's name within `folder` when it lies directly in it (the only files an editor
// writes); empty otherwise.
std::string nameInFolder(const std::filesystem::path& folder, const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::path a = std::filesystem::weakly_canonical(folder, error);
  if (error) return {};
  const std::filesystem::path b = std::filesystem::weakly_canonical(
      file.parent_path().empty() ? "." : file.parent_path(), error);
  if (error || a != b) return {};
  const std::string name = file.filename().string();
  return OutputFolder::isPlainName(name) ? name : std::string();
}

void writeInFolder(const std::filesystem::path& folder, const std::string& name,
                   const std::string& bytes) {
  OutputTarget out(OutputFolder(folder), name);
  if (std::fwrite(bytes.data(), 1, bytes.size(), out.stream()) != bytes.size())
    throw std::runtime_error((folder / name).string() + ": cannot write the file");
  out.commit();
}

}  // namespace

PaletteEditor::PaletteEditor(std::filesystem::path modelFolder, std::string lsystemStem,
                             const ColorFiles& files)
    : folder_(modelFolder.empty() ? "." : std::move(modelFolder)), stem_(std::move(lsystemStem)) {
  auto add = [this](int bank, const std::filesystem::path& path, PaletteDocument::Kind kind) {
    PaletteDocument empty;
    empty.kind = kind;
    files_.push_back(File{path, bank, EditHistory<PaletteDocument>(empty), {}});
    read(files_.back());
  };
  for (const auto& [bank, path] : files.colormaps) add(bank, path, PaletteDocument::Kind::ColorMap);
  for (const auto& [bank, path] : files.materials)
    add(bank, path, PaletteDocument::Kind::Materials);
  std::sort(files_.begin(), files_.end(),
            [](const File& a, const File& b) { return a.bank < b.bank; });
}

void PaletteEditor::read(File& file) {
  PaletteDocument::Kind kind = file.history.current().kind;
  file.error.clear();
  try {
    file.history = EditHistory<PaletteDocument>(readPaletteDocument(file.path, kind));
  } catch (const DiagnosticError& e) {
    // The file stays as it is: the editor does not write what it could not read.
    file.error = e.diagnostic().text();
    PaletteDocument empty;
    empty.kind = kind;
    file.history = EditHistory<PaletteDocument>(empty);
  }
}

std::optional<std::size_t> PaletteEditor::fileOf(int index) const {
  if (index < 0) return std::nullopt;
  const int bank = index / kColorsPerBank + 1;
  // A later file for the same bank is drawn over an earlier one (the reader places them in
  // order, materials last).
  std::optional<std::size_t> found;
  for (std::size_t f = 0; f < files_.size(); ++f) {
    if (files_[f].bank == bank) found = f;
  }
  return found;
}

bool PaletteEditor::edit(std::size_t file, PaletteDocument next, bool continuing) {
  File& f = files_.at(file);
  if (!f.error.empty() || next.kind != f.history.current().kind) return false;
  if (next == f.history.current()) return true;
  if (continuing && lastEdited_ == file)
    f.history.replaceCurrent(std::move(next));
  else
    f.history.record(std::move(next));
  lastEdited_ = file;
  return true;
}

bool PaletteEditor::undo(std::size_t file) {
  return file < files_.size() && files_[file].history.undo();
}

bool PaletteEditor::redo(std::size_t file) {
  return file < files_.size() && files_[file].history.redo();
}

bool PaletteEditor::modified() const {
  return std::any_of(files_.begin(), files_.end(),
                     [](const File& f) { return f.history.modified(); });
}

std::string PaletteEditor::save(std::size_t file) {
  File& f = files_.at(file);
  if (!f.error.empty()) return f.error;
  const std::string name = nameInFolder(folder_, f.path);
  if (name.empty()) {
    return f.path.string() + ": not written: an editor writes only in the model's folder (" +
           folder_.string() + ")";
  }
  try {
    writeInFolder(folder_, name, paletteBytes(f.history.current()));
  } catch (const std::exception& e) {
    return e.what();
  }
  f.history.markSaved();
  return {};
}

void PaletteEditor::reload() {
  for (File& f : files_) {
    if (f.history.modified()) continue;
    // A file that still holds what the editor saved keeps its history (a save is read back by
    // the viewer's watcher as any change is); another program's change starts a new one.
    if (f.error.empty()) {
      try {
        if (readPaletteDocument(f.path, f.history.current().kind) == f.history.current()) continue;
      } catch (const DiagnosticError&) {
        // read() keeps the message.
      }
    }
    read(f);
  }
}

std::string PaletteEditor::create(PaletteDocument::Kind kind, const std::vector<Material>& shown) {
  const std::string name = stem_ + (kind == PaletteDocument::Kind::ColorMap ? ".map" : ".mat");
  for (const File& f : files_) {
    if (f.bank == 1) {
      return "the model has a colour file already: " + f.path.string();
    }
  }
  std::error_code error;
  if (std::filesystem::exists(std::filesystem::symlink_status(folder_ / name, error)))
    return (folder_ / name).string() + ": exists already; not replaced";
  // The builder takes a folder's colour file only when it is the only one (docs/files.md).
  for (const auto& entry : std::filesystem::directory_iterator(folder_, error)) {
    if (paletteKindOf(entry.path())) {
      return "the model's folder has the colour file " + entry.path().filename().string() +
             " already; name it with -m or -M to edit it";
    }
  }
  const PaletteDocument document = paletteFromMaterials(
      std::vector<Material>(
          shown.begin(),
          shown.begin() +
              std::min<std::ptrdiff_t>(kColorsPerBank, static_cast<std::ptrdiff_t>(shown.size()))),
      kind);
  try {
    writeInFolder(folder_, name, paletteBytes(document));
  } catch (const std::exception& e) {
    return e.what();
  }
  files_.insert(files_.begin(),
                File{folder_ / name, 1, EditHistory<PaletteDocument>(document), {}});
  if (lastEdited_) ++*lastEdited_;
  return {};
}

void PaletteEditor::apply(std::vector<Material>& materials) const {
  for (const File& f : files_) {
    if (!f.error.empty()) continue;
    const std::size_t start = static_cast<std::size_t>(f.bank - 1) * kColorsPerBank;
    if (materials.size() < start + kColorsPerBank) materials.resize(start + kColorsPerBank);
    const std::vector<Material> bank = paletteMaterials(f.history.current());
    std::copy(bank.begin(), bank.end(), materials.begin() + static_cast<std::ptrdiff_t>(start));
  }
}

}  // namespace hirsute
