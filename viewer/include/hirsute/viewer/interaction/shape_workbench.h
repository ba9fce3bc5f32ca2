// The model's shapes as the viewer's editors change them (docs/viewer.md, "Function curves",
// "Contours", "Surfaces"): the function curves (`.func`, `.fset`), the contours and curves
// (`.con`) and the Bézier surfaces (`.s`) the build read, each with its undo history. Every
// change is written to its file at once, atomically, as vlab's funcedit, cuspy and bezieredit
// write theirs for cpfg to read again, and the live model re-derives; undo and redo write the
// state they return to. Only files the view file named are opened, so nothing is written
// outside the model's folder.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "hirsute/interpreter/surface.h"
#include "hirsute/lsys/function_curve.h"
#include "hirsute/viewer/interaction/edit_history.h"
#include "hirsute/viewer/interaction/model_worker.h"
#include "hirsute/viewer/interaction/view_script.h"

namespace hirsute {

template <typename File>
struct ShapeDocument {
  std::filesystem::path path;
  std::vector<std::string> names;  // what the view script calls it: file name, stem, its names
  EditHistory<File> history;
  std::string written;  // the text last read or written, to tell an edit made elsewhere
  // A version 0 `.func`'s samples come from its `function:` line (0: none); cpfg evaluates it
  // through a table of that many.
  int viewSamples = 0;
};

using CurveDocument = ShapeDocument<CurveFile>;
using SurfaceDocument = ShapeDocument<SurfaceFile>;

class ShapeWorkbench {
 public:
  // Takes the files a build read: new ones are opened, ones no longer named are closed, and one
  // changed on disk by someone else is read again (its history starts anew). A file that does
  // not read is left out; the build reported it.
  void follow(const ViewerModel& model, const std::filesystem::path& modelFolder);

  std::vector<CurveDocument>& functions() { return functions_; }
  std::vector<CurveDocument>& contours() { return contours_; }
  std::vector<SurfaceDocument>& surfaces() { return surfaces_; }
  int contourSides() const { return contourSides_; }

  // Which editor panels are open, on which document (and function of a set): the window's
  // panels show them, the script's `… NAME open|close` sets them.
  struct EditorView {
    bool open = false;
    std::size_t document = 0, block = 0;
  };
  EditorView functionView, contourView, surfaceView;

  // An edit of a document, made by `edit` on a copy of its present state (it returns an empty
  // string, or why the edit cannot be made). A new step of the history, or (`newStep` false: a
  // drag going on) a change of the present one. Written at once unless `writeNow` is false (the
  // window writes a long drag a few times a second). Returns the message of a refusal or of a
  // failed write.
  template <typename File, typename Change>
  std::string edit(ShapeDocument<File>& document, Change&& change, bool newStep,
                   bool writeNow = true) {
    File next = document.history.current();
    if (std::string refused = change(next); !refused.empty()) return refused;
    if (newStep) {
      document.history.record(std::move(next));
    } else {
      document.history.replaceCurrent(std::move(next));
    }
    return writeNow ? save(document) : std::string();
  }
  template <typename File>
  std::string undo(ShapeDocument<File>& document) {
    if (!document.history.undo()) return "nothing to undo in " + document.path.filename().string();
    return save(document);
  }
  template <typename File>
  std::string redo(ShapeDocument<File>& document) {
    if (!document.history.redo()) return "nothing to redo in " + document.path.filename().string();
    return save(document);
  }
  // Writes the present state when it differs from the file.
  std::string save(CurveDocument& document);
  std::string save(SurfaceDocument& document);

  // The view script's `function`, `contour` and `surface` commands (view_script.h). Returns
  // the message of a refusal, empty when done.
  std::string run(const ViewCommand& command);

  // The files written since the last call: the live model re-derives from them.
  std::vector<std::filesystem::path> takeWritten();

 private:
  std::string write(const std::filesystem::path& path, const std::string& text);

  std::filesystem::path folder_;
  std::vector<CurveDocument> functions_, contours_;
  std::vector<SurfaceDocument> surfaces_;
  int contourSides_ = 8;
  std::vector<std::filesystem::path> written_;
};

// Checks a parsed `function`, `contour` or `surface` command's action and its numbers
// (view_script.cpp); throws DiagnosticError at the command.
void checkShapeCommand(const ViewCommand& command);

}  // namespace hirsute
