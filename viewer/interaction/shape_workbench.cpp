#include "hirsute/viewer/interaction/shape_workbench.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hirsute/core/diagnostic.h"
#include "hirsute/core/edited_text.h"
#include "hirsute/core/model_folder.h"

namespace hirsute {
namespace {

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path normal(const std::filesystem::path& file) {
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(file, error);
  return (error ? file : absolute).lexically_normal();
}

// The script's names of a document: its file name and stem, then the names given inside.
std::vector<std::string> fileNames(const std::filesystem::path& path) {
  return {path.filename().string(), path.stem().string()};
}

// Opens (or keeps) the documents of `paths`, in their order; `open` reads one.
template <typename File, typename Open>
void followFiles(std::vector<ShapeDocument<File>>& documents,
                 const std::vector<std::filesystem::path>& paths, Open&& open) {
  std::vector<ShapeDocument<File>> kept;
  for (const std::filesystem::path& given : paths) {
    const std::filesystem::path path = normal(given);
    if (std::any_of(kept.begin(), kept.end(), [&](const auto& d) { return d.path == path; }))
      continue;
    const std::string text = readText(path);
    auto same = std::find_if(documents.begin(), documents.end(),
                             [&](const auto& d) { return d.path == path; });
    if (same != documents.end() && same->written == text) {
      kept.push_back(std::move(*same));
      continue;
    }
    try {
      File file = open(text, path);
      std::vector<std::string> names = fileNames(path);
      kept.push_back({path, std::move(names), EditHistory<File>(std::move(file)), text});
    } catch (const DiagnosticError&) {
      // The build reports a file that does not read; the editor leaves it out.
    }
  }
  documents = std::move(kept);
}

// The document the script names; null when none.
template <typename File>
ShapeDocument<File>* named(std::vector<ShapeDocument<File>>& documents, const std::string& name) {
  for (ShapeDocument<File>& document : documents) {
    if (std::find(document.names.begin(), document.names.end(), name) != document.names.end())
      return &document;
  }
  return nullptr;
}

std::string namesOf(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text.empty() ? "none" : text;
}

// A 1-based point number of the script as an index below `count`.
bool pointIndex(double number, std::size_t count, std::size_t& index) {
  if (number != std::floor(number) || number < 1 || number > static_cast<double>(count))
    return false;
  index = static_cast<std::size_t>(number) - 1;
  return true;
}

std::string noPoint(double number, std::size_t count) {
  return "no point " + formatFixed(number, 0) + ": the points are numbered 1 to " +
         std::to_string(count);
}

}  // namespace

void ShapeWorkbench::follow(const ViewerModel& model, const std::filesystem::path& modelFolder) {
  folder_ = normal(modelFolder);
  contourSides_ = model.view.contourSides;
  followFiles(functions_, model.functionFiles, [](const std::string& text, const auto& path) {
    const bool set = path.extension() == ".fset";
    return CurveFile::parse(text, path.string(),
                            set ? CurveFile::Kind::FunctionSet : CurveFile::Kind::Function);
  });
  for (CurveDocument& document : functions_) {
    for (std::size_t i = 0; i < model.functionFiles.size() && i < model.functionSamples.size();
         ++i) {
      if (normal(model.functionFiles[i]) == document.path)
        document.viewSamples = model.functionSamples[i];
    }
    // A function is named by its `name:` too (a function set's items only by theirs).
    for (const CurveFileBlock& block : document.history.current().blocks()) {
      if (!block.name.empty() && !named(functions_, block.name))
        document.names.push_back(block.name);
    }
  }
  std::vector<std::filesystem::path> contourFiles;
  for (const ContourDeclaration& contour : model.view.contours)
    contourFiles.push_back(contour.file);
  for (const std::filesystem::path& curve : model.curveFiles) contourFiles.push_back(curve);
  followFiles(contours_, contourFiles, [](const std::string& text, const auto& path) {
    return CurveFile::parse(text, path.string(), CurveFile::Kind::Contour);
  });
  std::vector<std::filesystem::path> surfaceFiles;
  for (const SurfaceDeclaration& surface : model.view.surfaces) {
    if (std::filesystem::path(surface.file).extension() == ".s")
      surfaceFiles.push_back(surface.file);
  }
  followFiles(surfaces_, surfaceFiles, [](const std::string& text, const auto& path) {
    return SurfaceFile::parse(text, path.string());
  });
  for (SurfaceDocument& document : surfaces_) {
    // A surface is named by the letter `~X` draws it with too.
    for (const SurfaceDeclaration& surface : model.view.surfaces) {
      if (normal(surface.file) == document.path)
        document.names.push_back(std::string(1, surface.id));
    }
  }
}

std::string ShapeWorkbench::write(const std::filesystem::path& path, const std::string& text) {
  // Only a file beneath the model's folder is written (it was named by the view file, which
  // the reader confined there; checked again, as every write of a model's file is).
  const std::filesystem::path relative = path.lexically_relative(folder_);
  const std::string refusal = relative.empty() ? "outside the model's folder"
                                               : ModelFolder(folder_).refusal(relative.string());
  if (!refusal.empty() || relative.string().starts_with(".."))
    return "hirsute: error: cannot write " + path.string() + ": " +
           (refusal.empty() ? "outside the model's folder" : refusal);
  try {
    writeFileAtomically(path, text);
  } catch (const std::exception& error) {
    return std::string("hirsute: error: ") + error.what();
  }
  written_.push_back(path);
  return std::string();
}

std::string ShapeWorkbench::save(CurveDocument& document) {
  const std::string text = document.history.current().text();
  if (text == document.written) return std::string();
  std::string failure = write(document.path, text);
  if (failure.empty()) {
    document.written = text;
    document.history.markSaved();
  }
  return failure;
}

std::string ShapeWorkbench::save(SurfaceDocument& document) {
  const std::string text = document.history.current().text();
  if (text == document.written) return std::string();
  std::string failure = write(document.path, text);
  if (failure.empty()) {
    document.written = text;
    document.history.markSaved();
  }
  return failure;
}

std::vector<std::filesystem::path> ShapeWorkbench::takeWritten() {
  return std::exchange(written_, {});
}

std::string ShapeWorkbench::run(const ViewCommand& command) {
  const std::string& editor = command.words[0];
  const std::string& name = command.words[1];
  const std::string& action = command.words[2];
  const std::vector<double>& n = command.numbers;

  if (editor == "surface") {
    SurfaceDocument* document = named(surfaces_, name);
    if (!document) {
      std::vector<std::string> all;
      for (const auto& d : surfaces_) all.push_back(d.names.front());
      return "the model has no surface '" + name + "' (its .s surfaces: " + namesOf(all) + ")";
    }
    if (action == "open" || action == "close") {
      surfaceView = {action == "open", static_cast<std::size_t>(document - surfaces_.data()), 0};
      return std::string();
    }
    if (action == "undo") return undo(*document);
    if (action == "redo") return redo(*document);
    if (action == "save") return save(*document);
    // point I X Y Z: the points of patch k are 16(k - 1) + 1 … 16k, row by row.
    const std::size_t count = 16 * document->history.current().surface().patches.size();
    std::size_t index = 0;
    if (!pointIndex(n[0], count, index)) return noPoint(n[0], count);
    const glm::dvec3 point(roundToMicro(n[1]), roundToMicro(n[2]), roundToMicro(n[3]));
    return edit(
        *document, [&](SurfaceFile& file) { return file.setPoint(index / 16, index % 16, point); },
        true);
  }

  const bool function = editor == "function";
  std::vector<CurveDocument>& documents = function ? functions_ : contours_;
  CurveDocument* document = named(documents, name);
  if (!document) {
    std::vector<std::string> all;
    for (const auto& d : documents) {
      all.push_back(d.names.front());
      if (function) {
        for (const CurveFileBlock& block : d.history.current().blocks())
          if (!block.name.empty()) all.push_back(block.name);
      }
    }
    return "the model has no " + editor + " '" + name + "' (its " + editor + "s: " + namesOf(all) +
           ")";
  }
  // The function of a set named by its item's name; the first block otherwise.
  std::size_t block = 0;
  const std::vector<CurveFileBlock>& blocks = document->history.current().blocks();
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b].name == name) block = b;
  }
  if (action == "open" || action == "close") {
    (function ? functionView : contourView) = {
        action == "open", static_cast<std::size_t>(document - documents.data()), block};
    return std::string();
  }
  if (action == "undo") return undo(*document);
  if (action == "redo") return redo(*document);
  if (action == "save") return save(*document);
  const std::size_t count = blocks[block].rows.size();
  std::size_t index = 0;
  const auto point = [&](std::size_t first) {
    return std::array<double, 3>{roundToMicro(n[first]), roundToMicro(n[first + 1]),
                                 n.size() > first + 2 ? roundToMicro(n[first + 2]) : 0.0};
  };
  if (action == "point") {
    if (!pointIndex(n[0], count, index)) return noPoint(n[0], count);
    return edit(
        *document, [&](CurveFile& file) { return file.setPoint(block, index, point(1)); }, true);
  }
  if (action == "remove") {
    if (!pointIndex(n[0], count, index)) return noPoint(n[0], count);
    return edit(
        *document, [&](CurveFile& file) { return file.removePoint(block, index); }, true);
  }
  // add: a function's point goes where its x falls; a contour's before point I (I = count + 1:
  // after the last).
  if (function) {
    const double x = roundToMicro(n[0]);
    const std::vector<CurveFileRow>& rows = blocks[block].rows;
    index = static_cast<std::size_t>(
        std::upper_bound(rows.begin(), rows.end(), x,
                         [](double v, const CurveFileRow& row) { return v < row.point[0]; }) -
        rows.begin());
    return edit(
        *document, [&](CurveFile& file) { return file.insertPoint(block, index, point(0)); }, true);
  }
  if (!pointIndex(n[0], count + 1, index)) return noPoint(n[0], count + 1);
  return edit(
      *document, [&](CurveFile& file) { return file.insertPoint(block, index, point(1)); }, true);
}

void checkShapeCommand(const ViewCommand& command) {
  const std::string& editor = command.words[0];
  if (command.words.size() < 3) {
    throw DiagnosticError(command.where, "'" + editor + "' takes a name and an action: " + editor +
                                             " NAME point|add|remove|undo|redo|save|open|close …");
  }
  const std::string& action = command.words[2];
  const std::size_t given = command.numbers.size();
  std::size_t low = 0, high = 0;
  std::string usage;
  if (action == "undo" || action == "redo" || action == "save" || action == "open" ||
      action == "close") {
    usage = editor + " NAME " + action;
  } else if (editor == "surface" && action == "point") {
    low = high = 4;
    usage = "surface NAME point I X Y Z";
  } else if (editor == "function" && action == "point") {
    low = high = 3;
    usage = "function NAME point I X Y";
  } else if (editor == "function" && action == "add") {
    low = high = 2;
    usage = "function NAME add X Y";
  } else if (editor == "contour" && (action == "point" || action == "add")) {
    low = 3;
    high = 4;
    usage = "contour NAME " + action + " I X Y [Z]";
  } else if (editor != "surface" && action == "remove") {
    low = high = 1;
    usage = editor + " NAME remove I";
  } else {
    throw DiagnosticError(
        command.where,
        "unknown " + editor + " action '" + action + "'; expected " +
            (editor == "surface" ? "point, undo, redo, save, open or close"
                                 : "point, add, remove, undo, redo, save, open or close"));
  }
  if (given < low || given > high) throw DiagnosticError(command.where, "expected '" + usage + "'");
}

}  // namespace hirsute
