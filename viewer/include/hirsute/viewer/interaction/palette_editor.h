// The palette and material editors' session (docs/viewer.md, "Editors"): the model's colour
// files (the .map or .mat of each colour bank, as `-m`/`-M` or the model's folder name them),
// each with its undo history (edit_history.h), the materials the plant is drawn with while edits
// are unsaved, and the saving: cpfg's binary format, written under a temporary name in the
// model's folder and renamed over the file. A file outside the model's folder is edited but not
// written; a file cpfg's format cannot hold (a colour map that is not 768 bytes) is refused.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hirsute/interpreter/model_resources.h"
#include "hirsute/viewer/interaction/edit_history.h"
#include "hirsute/viewer/interaction/palette_document.h"

namespace hirsute {

class PaletteEditor {
 public:
  struct File {
    std::filesystem::path path;
    int bank = 1;  // cpfg's -mN / -MN: indices 256·(N−1) … 256·N−1
    EditHistory<PaletteDocument> history;
    std::string error;  // why the file cannot be edited (it was refused when read); empty if it can
  };

  // `modelFolder`: the .l's folder, the only folder saved into. `lsystemStem` names the file a
  // model without a colour file creates (`STEM.map`, `STEM.mat`).
  PaletteEditor(std::filesystem::path modelFolder, std::string lsystemStem,
                const ColorFiles& files);

  const std::vector<File>& files() const { return files_; }
  bool empty() const { return files_.empty(); }
  // The file of colour index `index` (0 … 256·banks−1), or none.
  std::optional<std::size_t> fileOf(int index) const;

  // A change to file `file`'s document: a new step of its history, or with `continuing` the
  // present step changed (a drag). Returns false for a file that cannot be edited.
  bool edit(std::size_t file, PaletteDocument next, bool continuing = false);
  bool undo(std::size_t file);
  bool redo(std::size_t file);
  // The file last edited (undo and redo without a file name act on it); none before an edit.
  std::optional<std::size_t> lastEdited() const { return lastEdited_; }
  bool modified() const;

  // Writes the file's document; returns the message (empty on success): "FILE: …".
  std::string save(std::size_t file);
  // Reads the files again after they changed on disk; a file with unsaved edits keeps them.
  void reload();
  // Creates STEM.map or STEM.mat in the model's folder holding `shown` (the palette the plant is
  // drawn with: the default colours of a model without a colour file), and edits it as bank 1.
  // Returns the message (empty on success); a file of that name is not replaced.
  std::string create(PaletteDocument::Kind kind, const std::vector<Material>& shown);

  // The plant's materials with every file's present state in its bank (the scene's palette is
  // 256 materials a bank); `materials` grows to hold the banks edited.
  void apply(std::vector<Material>& materials) const;

 private:
  void read(File& file);

  std::filesystem::path folder_;
  std::string stem_;
  std::vector<File> files_;
  std::optional<std::size_t> lastEdited_;
};

}  // namespace hirsute
