// The viewer's editors without a window (docs/viewer.md, "Editors"): every colour map, material
// file and control panel shipped or in the conformance corpus is read and written back byte for
// byte; an edit changes the bytes it names and no others; files the formats cannot hold are
// refused with their place; saving writes only in the model's folder; and the live model draws
// palette edits at once without a build, undoes them, and binds a panel's controls to the .l's
// #defines as vlab's awkped does.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <thread>

#include "hirsute/viewer/interaction/control_panel.h"
#include "hirsute/viewer/interaction/live_model.h"
#include "hirsute/viewer/interaction/palette_document.h"
#include "hirsute/viewer/interaction/palette_editor.h"
#include "hirsute/viewer/interaction/panel_editor.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const fs::path kSource = HIRSUTE_SOURCE_DIR;
const fs::path kFixtures = kSource / "tests/fixtures/viewer/editors";
const fs::path kConformance = kSource / ".." / "shared" / "conformance";

std::string readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

std::vector<fs::path> filesUnder(const fs::path& folder,
                                 const std::vector<std::string>& extensions) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::string extension = entry.path().extension().string();
    if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end())
      found.push_back(entry.path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

// Each file read by its editor and written back: the same bytes. Returns how many.
std::size_t expectRoundTrips(const fs::path& folder) {
  std::size_t count = 0;
  for (const fs::path& file : filesUnder(folder, {".map", ".mat", ".pnl"})) {
    const std::string bytes = readBytes(file);
    std::string written;
    if (file.extension() == ".pnl") {
      written = controlPanelText(parseControlPanel(bytes, file.string()));
    } else {
      written = paletteBytes(readPaletteDocument(file, *paletteKindOf(file)));
    }
    EXPECT_EQ(written, bytes) << file;
    ++count;
  }
  return count;
}

// A temporary model folder, removed at the end.
struct TempFolder {
  fs::path path;
  explicit TempFolder(const std::string& name) {
    path =
        fs::temp_directory_path() / ("hirsute_editors_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
};

TEST(EditorFilesTest, EveryShippedColourFileAndPanelIsWrittenBackByteForByte) {
  const std::size_t count = expectRoundTrips(kSource / "models");
  EXPECT_GE(count, 30u) << "the shipped models' .map, .mat and .pnl files";
  EXPECT_FALSE(filesUnder(kSource / "models", {".pnl"}).empty()) << "a shipped model has a panel";
}

TEST(EditorFilesTest, EveryConformanceColourFileAndPanelIsWrittenBackByteForByte) {
  if (!fs::is_directory(kConformance))
    GTEST_SKIP() << kConformance << " is absent (the conformance corpus beside the repository)";
  EXPECT_GE(expectRoundTrips(kConformance), 40u);
}

TEST(EditorFilesTest, TheFixturePanelsAreWrittenBackByteForByte) {
  for (const char* name : {"plant.pnl", "crlf.pnl"}) {
    const std::string bytes = readBytes(kFixtures / name);
    EXPECT_EQ(controlPanelText(parseControlPanel(bytes, name)), bytes) << name;
  }
  // Without a final new line, too.
  const std::string cut = "panel name: P\ntype: LABEL\nname: x";
  EXPECT_EQ(controlPanelText(parseControlPanel(cut, "cut.pnl")), cut);
}

TEST(PaletteDocumentTest, AColourEditChangesItsThreeBytesOnly) {
  const fs::path file = kSource / "models/pulsatilla/pulsatilla.map";
  PaletteDocument document = readPaletteDocument(file, PaletteDocument::Kind::ColorMap);
  const std::string before = paletteBytes(document);
  setColor(document, 12, glm::vec3(0.8f, 0.2f, 0.1f));
  const std::string after = paletteBytes(document);
  ASSERT_EQ(after.size(), 768u);
  for (std::size_t i = 0; i < after.size(); ++i) {
    if (i / 3 == 12) continue;
    EXPECT_EQ(after[i], before[i]) << "byte " << i;
  }
  EXPECT_EQ(static_cast<unsigned char>(after[36]), 204);  // 0.8 · 255
  EXPECT_EQ(static_cast<unsigned char>(after[37]), 51);
  EXPECT_EQ(static_cast<unsigned char>(after[38]), 26);
  EXPECT_EQ(paletteMaterials(document)[12].diffuse, glm::vec3(204, 51, 26) / 255.0f);
}

TEST(PaletteDocumentTest, AMaterialEditChangesTheLastRecordOfItsIndexOrAddsOne) {
  PaletteDocument document;
  document.kind = PaletteDocument::Kind::Materials;
  MaterialRecord first;
  first.index = 3;
  first.shininess = 200;  // more than OpenGL takes: kept as it is
  MaterialRecord second = first;
  second.diffuse = {1, 2, 3};
  document.records = {first, second};
  setMaterialField(document, 3, MaterialField::Diffuse, glm::vec3(0.5f, 0.5f, 0.5f));
  ASSERT_EQ(document.records.size(), 2u);
  EXPECT_EQ(document.records[0], first) << "the earlier record stays as it was";
  EXPECT_EQ(document.records[1].diffuse, (std::array<std::uint8_t, 3>{128, 128, 128}));
  EXPECT_EQ(document.records[1].shininess, 200) << "the fields not edited keep their bytes";
  EXPECT_EQ(paletteMaterials(document)[3].shininess, 128.0f);

  setMaterialField(document, 9, MaterialField::Transparency, glm::vec3(1.0f));
  ASSERT_EQ(document.records.size(), 3u);
  EXPECT_EQ(document.records[2].index, 9);
  EXPECT_EQ(document.records[2].transparency, 255);
  // The rest is OpenGL's default material, which the index showed without a record.
  EXPECT_EQ(document.records[2].ambient, (std::array<std::uint8_t, 3>{51, 51, 51}));
  EXPECT_EQ(document.records[2].diffuse, (std::array<std::uint8_t, 3>{204, 204, 204}));
  setMaterialField(document, 9, MaterialField::Shininess, glm::vec3(300.0f));
  EXPECT_EQ(document.records[2].shininess, 128) << "the editor writes what OpenGL takes";
  EXPECT_EQ(paletteBytes(document).size(), 45u);
}

TEST(PaletteEditorTest, EditsAreUndoneAndSavedAtomicallyInTheModelsFolder) {
  TempFolder folder("save");
  const fs::path map = folder.path / "plant.map";
  fs::copy_file(kSource / "models/pulsatilla/pulsatilla.map", map);
  const std::string original = readBytes(map);
  ColorFiles files;
  files.colormaps.push_back({1, map});
  PaletteEditor editor(folder.path, "plant", files);
  ASSERT_EQ(editor.files().size(), 1u);
  ASSERT_EQ(editor.fileOf(12), std::optional<std::size_t>(0));
  EXPECT_FALSE(editor.fileOf(300)) << "bank 2 has no file";

  PaletteDocument next = editor.files()[0].history.current();
  setColor(next, 12, glm::vec3(1, 0, 0));
  ASSERT_TRUE(editor.edit(0, next));
  // A drag: one step, whatever the moves.
  setColor(next, 12, glm::vec3(0, 1, 0));
  editor.edit(0, next, true);
  setColor(next, 12, glm::vec3(0, 0, 1));
  editor.edit(0, next, true);
  EXPECT_TRUE(editor.modified());
  EXPECT_EQ(readBytes(map), original) << "nothing is written before Save";

  std::vector<Material> drawn(256);
  editor.apply(drawn);
  EXPECT_EQ(drawn[12].diffuse, glm::vec3(0, 0, 1));

  ASSERT_TRUE(editor.undo(0));
  EXPECT_FALSE(editor.modified());
  EXPECT_FALSE(editor.undo(0)) << "the drag was one step";
  ASSERT_TRUE(editor.redo(0));
  ASSERT_EQ(editor.save(0), "");
  EXPECT_FALSE(editor.modified());
  const std::string saved = readBytes(map);
  EXPECT_EQ(saved.substr(36, 3), std::string("\0\0\xff", 3));
  EXPECT_EQ(saved.substr(0, 36), original.substr(0, 36));
  // Nothing is left beside it (the temporary file was renamed over it).
  EXPECT_EQ(std::distance(fs::directory_iterator(folder.path), fs::directory_iterator()), 1);
  // The viewer reads its own save back (its watcher sees the change): the history stays.
  editor.reload();
  EXPECT_TRUE(editor.undo(0)) << "undo reaches past the save";
  // Another program's change starts the history anew.
  ASSERT_TRUE(editor.redo(0));
  writeBytes(map, original);
  editor.reload();
  EXPECT_FALSE(editor.files()[0].history.canUndo());
  EXPECT_EQ(paletteBytes(editor.files()[0].history.current()), original);
}

TEST(PanelEditorTest, APanelMadeSavedAndReadBackKeepsItsHistory) {
  TempFolder folder("panel_history");
  fs::copy_file(kFixtures / "plant.l", folder.path / "plant.l");
  PanelEditor editor(folder.path, "plant");
  EXPECT_TRUE(editor.panels().empty());
  const auto constants = findDefineConstants(readBytes(kFixtures / "plant.l"));
  std::size_t created = 99;
  ASSERT_EQ(editor.create(constants, &created), "");
  ASSERT_EQ(created, 0u);
  const std::string made = readBytes(folder.path / "plant.pnl");
  EXPECT_EQ(made, controlPanelText(makeControlPanel(constants, "plant", "plant.l")));
  EXPECT_NE(editor.create(constants), "") << "an existing panel is not replaced";

  ControlPanel next = editor.panels()[0].history.current();
  setPanelRange(next, 0, 1, 40, "plant.pnl");
  ASSERT_TRUE(editor.edit(0, next));
  ASSERT_EQ(editor.save(0), "");
  editor.reload();
  ASSERT_EQ(editor.panels().size(), 1u);
  EXPECT_EQ(editor.lastEdited(), std::optional<std::size_t>(0));
  ASSERT_TRUE(editor.undo(0));
  ASSERT_EQ(editor.save(0), "");
  EXPECT_EQ(readBytes(folder.path / "plant.pnl"), made);
  // A control's #define, as awkped sets it: the value over the message's scale.
  const auto define = editor.activate(0, 1, 305, constants);
  ASSERT_TRUE(define);
  EXPECT_EQ(define->first, "ANGLE");
  EXPECT_EQ(define->second, "30.5");
}

TEST(PaletteEditorTest, AFileOutsideTheModelsFolderIsNotWritten) {
  TempFolder model("inside"), elsewhere("outside");
  const fs::path map = elsewhere.path / "shared.map";
  fs::copy_file(kSource / "models/pulsatilla/pulsatilla.map", map);
  const std::string original = readBytes(map);
  ColorFiles files;
  files.colormaps.push_back({1, map});
  PaletteEditor editor(model.path, "plant", files);
  PaletteDocument next = editor.files()[0].history.current();
  setColor(next, 1, glm::vec3(1, 1, 1));
  ASSERT_TRUE(editor.edit(0, next));
  const std::string message = editor.save(0);
  EXPECT_NE(message.find("only in the model's folder"), std::string::npos) << message;
  EXPECT_EQ(readBytes(map), original);
  EXPECT_TRUE(editor.modified());
}

TEST(PaletteEditorTest, AFileTheFormatCannotHoldIsRefusedAndLeftAlone) {
  TempFolder folder("refused");
  const fs::path map = folder.path / "short.map";
  writeBytes(map, std::string(700, '\x10'));
  const fs::path mat = folder.path / "torn.mat";
  writeBytes(mat, std::string(20, '\x01'));
  ColorFiles files;
  files.colormaps.push_back({1, map});
  files.materials.push_back({2, mat});
  PaletteEditor editor(folder.path, "plant", files);
  ASSERT_EQ(editor.files().size(), 2u);
  EXPECT_NE(editor.files()[0].error.find("exactly 768 bytes"), std::string::npos)
      << editor.files()[0].error;
  EXPECT_NE(editor.files()[1].error.find("5 left over"), std::string::npos)
      << editor.files()[1].error;
  PaletteDocument next;
  EXPECT_FALSE(editor.edit(0, next));
  EXPECT_NE(editor.save(0), "");
  EXPECT_EQ(readBytes(map), std::string(700, '\x10'));
}

TEST(PaletteEditorTest, AModelWithoutAColourFileCreatesOneOfItsColours) {
  TempFolder folder("create");
  PaletteEditor editor(folder.path, "plant", ColorFiles{});
  EXPECT_TRUE(editor.empty());
  ASSERT_EQ(editor.create(PaletteDocument::Kind::ColorMap, defaultPalette()), "");
  ASSERT_EQ(editor.files().size(), 1u);
  const fs::path map = folder.path / "plant.map";
  ASSERT_TRUE(fs::is_regular_file(map));
  // The default palette written down: what the plant showed, now the user's.
  const std::vector<Material> read = loadColorMap(map);
  const std::vector<Material> shown = defaultPalette();
  for (int i = 0; i < 256; ++i)
    EXPECT_LT(glm::length(read[i].diffuse - shown[i].diffuse), 0.003f) << i;
  EXPECT_NE(editor.create(PaletteDocument::Kind::Materials, shown), "")
      << "bank 1 has its file now";
  // A second colour file in the folder would leave the builder without one (docs/files.md).
  PaletteEditor another(folder.path, "other", ColorFiles{});
  const std::string refused = another.create(PaletteDocument::Kind::Materials, shown);
  EXPECT_NE(refused.find("has the colour file plant.map already"), std::string::npos) << refused;
  EXPECT_FALSE(fs::exists(folder.path / "other.mat"));
}

TEST(ControlPanelTest, ItemsAndTheirDefineMessagesAreRead) {
  const ControlPanel panel = parseControlPanel(readBytes(kFixtures / "plant.pnl"), "plant.pnl");
  EXPECT_EQ(panel.title, "Plant");
  EXPECT_EQ(panel.target, "plant.l");
  ASSERT_EQ(panel.items.size(), 9u);
  const PanelItem& angle = panel.items[1];
  EXPECT_EQ(angle.type, PanelItem::Type::Slider);
  EXPECT_EQ(angle.name, "Angle [degrees]");
  EXPECT_EQ(angle.minimum, 0);
  EXPECT_EQ(angle.maximum, 900);
  EXPECT_EQ(angle.value, 225);
  const auto message = defineMessage(angle.message);
  ASSERT_TRUE(message);
  EXPECT_EQ(message->name, "ANGLE");
  EXPECT_EQ(message->scale, 10);
  EXPECT_EQ(defineValueFor(*message, 46, false), "4.6");
  EXPECT_EQ(defineValueFor(DefineMessage{"STEPS", 1}, 6, true), "6");
  EXPECT_EQ(panel.items[5].name, "No") << "vlab's %Copy1 is not shown";
  EXPECT_EQ(panel.items[6].buttons, (std::vector<std::string>{"Yes", "No%Copy1"}));
  EXPECT_FALSE(defineMessage(panel.items[5].message)) << "a line/word message sets no #define";
  EXPECT_EQ(findPanelItem(panel, PanelItem::Type::Slider, "ANGLE"), std::optional<std::size_t>(1));
  EXPECT_EQ(findPanelItem(panel, PanelItem::Type::Slider, "Steps"), std::optional<std::size_t>(2));
}

TEST(ControlPanelTest, WhatAPanelCannotHoldIsRefusedAtItsLine) {
  auto messageOf = [](const char* name) {
    try {
      parseControlPanel(readBytes(kFixtures / name), name);
    } catch (const DiagnosticError& e) {
      return e.diagnostic().text();
    }
    return std::string("no error");
  };
  EXPECT_NE(messageOf("unknown_keyword.pnl")
                .find("unknown_keyword.pnl:5:1: error: unknown panel keyword 'width'"),
            std::string::npos)
      << messageOf("unknown_keyword.pnl");
  EXPECT_NE(messageOf("empty_range.pnl").find("empty_range.pnl:3:1: error:"), std::string::npos)
      << messageOf("empty_range.pnl");
  EXPECT_NE(messageOf("unknown_button.pnl")
                .find("unknown_button.pnl:5:1: error: the group names the button 'Off'"),
            std::string::npos)
      << messageOf("unknown_button.pnl");
  EXPECT_THROW(parseControlPanel(std::string(kMaxPanelBytes + 1, ' '), "huge.pnl"),
               DiagnosticError);
}

TEST(ControlPanelTest, EditsChangeOnlyTheirLines) {
  const std::string text = readBytes(kFixtures / "plant.pnl");
  ControlPanel panel = parseControlPanel(text, "plant.pnl");
  setPanelRange(panel, 2, 2, 12, "plant.pnl");
  setPanelValue(panel, 2, 5, "plant.pnl");
  std::string expected = text;
  expected.replace(expected.find("min/max:  1 8"), 13, "min/max:  2 12");
  expected.replace(expected.find("value:   4"), 10, "value:   5");
  EXPECT_EQ(controlPanelText(panel), expected);
  EXPECT_EQ(panel.items[2].maximum, 12);

  const std::string crlf = readBytes(kFixtures / "crlf.pnl");
  ControlPanel windows = parseControlPanel(crlf, "crlf.pnl");
  setPanelValue(windows, 0, 7, "crlf.pnl");
  std::string expectedCrlf = crlf;
  expectedCrlf.replace(expectedCrlf.find("value: 3\r"), 9, "value: 7\r");
  EXPECT_EQ(controlPanelText(windows), expectedCrlf);

  removePanelItem(panel, 1, "plant.pnl");
  EXPECT_FALSE(findPanelItem(panel, PanelItem::Type::Slider, "ANGLE"));
  EXPECT_EQ(controlPanelText(panel).find("Angle"), std::string::npos);
}

TEST(ControlPanelTest, APanelMadeFromTheConstantsBindsEachOne) {
  const auto constants = findDefineConstants(readBytes(kFixtures / "plant.l"));
  ASSERT_EQ(constants.size(), 3u);
  const ControlPanel panel = makeControlPanel(constants, "plant", "plant.l");
  ASSERT_EQ(panel.items.size(), 3u);
  for (std::size_t i = 0; i < constants.size(); ++i) {
    const auto message = defineMessage(panel.items[i].message);
    ASSERT_TRUE(message) << panel.items[i].message;
    EXPECT_EQ(message->name, constants[i].name);
    // The slider's value, scaled back, is the constant's.
    EXPECT_DOUBLE_EQ(panel.items[i].value / message->scale, constants[i].value);
    EXPECT_LE(panel.items[i].minimum, panel.items[i].value);
    EXPECT_GE(panel.items[i].maximum, panel.items[i].value);
  }
  EXPECT_EQ(panel.items[1].message, "d ANGLE %d 10");
  EXPECT_EQ(panel.items[1].value, 225);
  // What it writes reads back the same.
  EXPECT_EQ(parseControlPanel(controlPanelText(panel), "plant.pnl"), panel);
}

// ---- the live model ----

// The window's side: the palettes it was given to draw.
struct PaletteView : LiveModelView {
  std::vector<std::vector<Material>> uploads;
  void upload(const ViewerModel& model) override { uploads.push_back(model.scene.materials); }
  void updateOrgan(std::string_view, const Scene&) override {}
  bool screenshot(const std::filesystem::path&, Shot) override { return true; }
  void measure(int) override {}
};

// A model whose scene is the palette of its colour file; builds and their #defines counted.
struct PaletteBuilder {
  explicit PaletteBuilder(fs::path file) : map(std::move(file)) {}
  fs::path map;
  std::mutex mutex;
  int builds = 0;
  std::map<std::string, std::string> defines;
  ModelBuilder builder() {
    return [this](const ModelRequest& request, BuildProgress&) {
      {
        std::lock_guard lock(mutex);
        ++builds;
        defines = request.defines;
      }
      auto model = std::make_shared<ViewerModel>();
      model->derivationLength = 4;
      model->steps = 4;
      model->scene.materials = loadColorMap(map);
      ModelBuild build;
      build.model = std::move(model);
      return build;
    };
  }
};

void runScript(LiveModel& live) {
  for (int i = 0; i < 4000 && !live.closed(); ++i) {
    live.update();
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_TRUE(live.closed());
}

TEST(LiveEditorsTest, AColourEditIsDrawnAtOnceWithoutABuildAndSavedWhenAsked) {
  TempFolder folder("live_colors");
  fs::copy_file(kFixtures / "plant.l", folder.path / "plant.l");
  fs::copy_file(kSource / "models/pulsatilla/pulsatilla.map", folder.path / "plant.map");
  const std::string original = readBytes(folder.path / "plant.map");
  LiveModelOptions options;
  options.lsystemFile = folder.path / "plant.l";
  options.watch = false;
  options.colorFiles.colormaps.push_back({1, folder.path / "plant.map"});
  options.script = parseViewScript(
      "color 12 1 0 0; color 12 0 0 1; undo; save colors; color 13 0 1 0; undo; redo; undo; quit",
      "--commands");
  PaletteBuilder builder{folder.path / "plant.map"};
  PaletteView view;
  LiveModel live(options, builder.builder(), view);
  runScript(live);
  EXPECT_EQ(live.exitCode(), 0);
  EXPECT_EQ(builder.builds, 1) << "colour edits need no build";
  // The first build, then each edit, undo and redo drawn.
  ASSERT_EQ(view.uploads.size(), 8u);
  EXPECT_EQ(view.uploads[1][12].diffuse, glm::vec3(1, 0, 0));
  EXPECT_EQ(view.uploads[2][12].diffuse, glm::vec3(0, 0, 1));
  EXPECT_EQ(view.uploads[3][12].diffuse, glm::vec3(1, 0, 0)) << "undo";
  EXPECT_EQ(view.uploads[5][13].diffuse, view.uploads[0][13].diffuse) << "undo of colour 13";
  const std::string saved = readBytes(folder.path / "plant.map");
  EXPECT_EQ(saved.substr(36, 3), std::string("\xff\0\0", 3)) << "saved after the undo";
  EXPECT_EQ(saved.substr(39), original.substr(39)) << "colour 13 was never saved";
}

TEST(LiveEditorsTest, APanelsSliderAndButtonSetTheirDefines) {
  TempFolder folder("live_panel");
  fs::copy_file(kFixtures / "plant.l", folder.path / "plant.l");
  fs::copy_file(kFixtures / "plant.pnl", folder.path / "plant.pnl");
  fs::copy_file(kSource / "models/pulsatilla/pulsatilla.map", folder.path / "plant.map");
  LiveModelOptions options;
  options.lsystemFile = folder.path / "plant.l";
  options.watch = false;
  options.script = parseViewScript(
      "panel slider ANGLE 450; panel button Leaves on; panel slider Steps 99; "
      "panel range Steps 2 12; save panel; undo panel; quit",
      "--commands");
  PaletteBuilder builder{folder.path / "plant.map"};
  PaletteView view;
  LiveModel live(options, builder.builder(), view);
  runScript(live);
  EXPECT_EQ(live.exitCode(), 0);
  EXPECT_EQ(builder.defines["ANGLE"], "45.0") << "450 / 10, as awkped divides";
  EXPECT_EQ(builder.defines["LEAVES"], "1");
  EXPECT_EQ(builder.defines["STEPS"], "8") << "a slider stays within its range";
  EXPECT_NE(readBytes(folder.path / "plant.pnl").find("min/max:  2 12"), std::string::npos);
  EXPECT_NE(readBytes(folder.path / "plant.l").find("#define ANGLE 22.5"), std::string::npos)
      << "the .l is written only by 'save'";
  EXPECT_TRUE(live.panels().panels()[0].history.modified()) << "undone after the save";
}

TEST(LiveEditorsTest, ACommandThatCannotBeDoneFailsTheScriptWithItsPlace) {
  TempFolder folder("live_fail");
  fs::copy_file(kFixtures / "plant.l", folder.path / "plant.l");
  fs::copy_file(kSource / "models/pulsatilla/pulsatilla.map", folder.path / "plant.map");
  LiveModelOptions options;
  options.lsystemFile = folder.path / "plant.l";
  options.watch = false;
  options.colorFiles.colormaps.push_back({1, folder.path / "plant.map"});
  options.script = parseViewScript("color 1 1 1 1; material 1 diffuse 1 0 0; quit", "--commands");
  PaletteBuilder builder{folder.path / "plant.map"};
  PaletteView view;
  testing::internal::CaptureStderr();
  LiveModel live(options, builder.builder(), view);
  runScript(live);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(live.exitCode(), 1);
  EXPECT_NE(err.find("--commands:1:16: error: no material file (.mat) holds material 1"),
            std::string::npos)
      << err;
}

TEST(LiveEditorsTest, ScriptMistakesAreFoundBeforeTheWindowOpens) {
  auto messageOf = [](const std::string& script) {
    try {
      parseViewScript(script, "s");
    } catch (const DiagnosticError& e) {
      return e.diagnostic().text();
    }
    return std::string("no error");
  };
  EXPECT_NE(messageOf("material 1 glossy 1").find("s:1:12: error: expected one of ambient"),
            std::string::npos);
  EXPECT_NE(messageOf("material 1 diffuse 1").find("takes three values"), std::string::npos);
  EXPECT_NE(messageOf("color 5000 1 1 1").find("from 0 to 3071"), std::string::npos);
  EXPECT_NE(messageOf("save everything").find("expected one of constants"), std::string::npos);
  EXPECT_NE(messageOf("panel slider A").find("'panel slider' takes 2 arguments"),
            std::string::npos);
  EXPECT_NE(messageOf("panel slider A 1.5").find("expected a whole number"), std::string::npos);
  EXPECT_EQ(messageOf("panel on; panel slider A 3; panel button B off; undo; redo colors; "
                      "save; save panel; create materials; colors on; controls off"),
            "no error");
}

}  // namespace
}  // namespace hirsute
