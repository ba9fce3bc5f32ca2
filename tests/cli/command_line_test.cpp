// One command-line grammar: every command that makes pictures takes `--size WIDTHxHEIGHT` with the
// same limits (the former --width and --height stay as hidden aliases), a picture's format is the
// one its name's extension names or the name is refused with the list, and `export --render`
// says so before it replaces an image it was not named.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "hirsute/viewer/view/png_image.h"
#include "support/run_hirsute.h"

namespace hirsute {
namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kHerb = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "herb";
const fs::path kCoat = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "coat-bending";

std::string firstBytes(const fs::path& file, std::size_t count) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes(count, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

std::vector<std::string> herb() {
  return {(kHerb / "herb.l").string(), (kHerb / "herb.v").string()};
}

std::vector<std::string> with(std::vector<std::string> first,
                              const std::vector<std::string>& more) {
  first.insert(first.end(), more.begin(), more.end());
  return first;
}

// Every command that makes a picture refuses the same bad sizes with the same words, and takes a
// good one.
TEST(CommandLineSize, EveryPictureCommandTakesSizeWithTheSameLimits) {
  TemporaryFolder folder;
  const std::vector<std::vector<std::string>> commands = {
      with({"render"}, with(herb(), {"-o", (folder.path() / "a.png").string()})),
      with({"view"}, herb()),
      with({"export"}, with(herb(), {"--pov", (folder.path() / "a.pov").string()})),
      {"simulate", (kCoat / "bending.l").string(), (kCoat / "bending.v").string(), "-o",
       (folder.path() / "frames").string()},
      {"render-frames", folder.path().string()},
  };
  for (const std::vector<std::string>& command : commands) {
    for (const std::string bad : {"0x10", "16385x10", "10x", "10", "-5x5", "1e3x10"}) {
      const RunResult run = runHirsute(with(command, {"--size", bad}));
      EXPECT_EQ(run.exitCode, 2) << command[0] << " --size " << bad << ": " << run.err;
      EXPECT_NE(run.err.find("'" + bad +
                             "' is not WIDTHxHEIGHT (as 1024x768) with each side from 1 "
                             "to 16384"),
                std::string::npos)
          << command[0] << ": " << run.err;
    }
    const RunResult help = runHirsute({command[0], "--help"});
    EXPECT_NE(help.out.find("--size"), std::string::npos) << command[0];
  }
}

// The former spellings still work, unlisted, and cannot be mixed with --size.
TEST(CommandLineSize, WidthAndHeightAreHiddenAliases) {
  TemporaryFolder folder;
  const fs::path pov = folder.path() / "a.pov";
  RunResult run = runHirsute(
      with({"export"}, with(herb(), {"--pov", pov.string(), "--width", "64", "--height", "48"})));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const RunResult sized = runHirsute(with(
      {"export"}, with(herb(), {"--pov", (folder.path() / "b.pov").string(), "--size", "64x48"})));
  ASSERT_EQ(sized.exitCode, 0) << sized.err;
  std::ifstream a(pov), b(folder.path() / "b.pov");
  const std::string aText{std::istreambuf_iterator<char>(a), {}};
  const std::string bText{std::istreambuf_iterator<char>(b), {}};
  // The same scene, but for the names in its first lines.
  const auto body = [](const std::string& text) { return text.substr(text.find("#version")); };
  EXPECT_NE(aText.find("+W64 +H48"), std::string::npos);
  EXPECT_NE(bText.find("+W64 +H48"), std::string::npos);
  EXPECT_TRUE(body(aText) == body(bText)) << "--width/--height and --size make the same scene";
  run = runHirsute({"export", "--help"});
  EXPECT_EQ(run.out.find("--width"), std::string::npos) << run.out;
  run = runHirsute(
      with({"export"}, with(herb(), {"--pov", pov.string(), "--size", "64x48", "--width", "10"})));
  EXPECT_EQ(run.exitCode, 2) << run.err;
}

TEST(CommandLineFormats, RenderWritesTheFormatTheNameSays) {
  TemporaryFolder folder;
  const fs::path jpeg = folder.path() / "plant.JPG", png = folder.path() / "plant.png";
  RunResult run =
      runHirsute(with({"render"}, with(herb(), {"-o", jpeg.string(), "--size", "48x32"})));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(firstBytes(jpeg, 3), "\xFF\xD8\xFF") << "a JPEG's start of image";
  run = runHirsute(with({"render"}, with(herb(), {"-o", png.string(), "--size", "48x32"})));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(firstBytes(png, 8), "\x89PNG\r\n\x1a\n");
}

TEST(CommandLineFormats, AnUnknownExtensionIsRefusedWithTheList) {
  TemporaryFolder folder;
  for (const std::string name : {"plant.tiff", "plant", "plant.png.bak"}) {
    const fs::path out = folder.path() / name;
    const RunResult run = runHirsute(with({"render"}, with(herb(), {"-o", out.string()})));
    EXPECT_EQ(run.exitCode, 2) << name;
    EXPECT_NE(run.err.find("the picture's format is chosen by its extension: .png, .jpg, .jpeg "
                           "(and .exr with --trace)"),
              std::string::npos)
        << run.err;
    EXPECT_FALSE(fs::exists(out)) << name;
  }
  // OpenEXR holds a traced picture's light; GL's picture has none to hold.
  const RunResult exr =
      runHirsute(with({"render"}, with(herb(), {"-o", (folder.path() / "plant.exr").string()})));
  EXPECT_EQ(exr.exitCode, 2);
  EXPECT_NE(exr.err.find("made by --trace only"), std::string::npos) << exr.err;
}

TEST(CommandLineFormats, ExportRenderSaysWhenItReplacesAnImageItWasNotNamed) {
  if (std::system("command -v povray >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "povray is not installed (scripts/install-deps.sh installs it)";
  TemporaryFolder folder;
  const fs::path pov = folder.path() / "herb.pov", image = folder.path() / "herb.png";
  const std::vector<std::string> exportHerb =
      with({"export"}, with(herb(), {"--pov", pov.string(), "--render", "--size", "32x24"}));
  RunResult run = runHirsute(exportHerb);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err.find("replacing"), std::string::npos) << run.err;
  ASSERT_TRUE(fs::exists(image));
  run = runHirsute(exportHerb);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("hirsute: note: replacing " + image.string() + " with the picture of " +
                         pov.string()),
            std::string::npos)
      << run.err;
  // --image names the picture: nothing is replaced, nothing said.
  const fs::path chosen = folder.path() / "chosen.png";
  run = runHirsute(with(exportHerb, {"--image", chosen.string()}));
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(run.err.find("replacing"), std::string::npos) << run.err;
  EXPECT_EQ(firstBytes(chosen, 8), "\x89PNG\r\n\x1a\n");
  run = runHirsute(with(exportHerb, {"--image", (folder.path() / "chosen.jpg").string()}));
  EXPECT_EQ(run.exitCode, 2) << run.err;
}

// The names of the entries of a help text's `Subcommands:` section.
std::vector<std::string> subcommandsIn(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help);
  bool inSection = false;
  for (std::string line; std::getline(lines, line);) {
    if (line == "Subcommands:") {
      inSection = true;
    } else if (inSection && line.rfind("  ", 0) == 0 && line.size() > 2 && line[2] != ' ') {
      names.push_back(line.substr(2, line.find(' ', 2) - 2));
    } else if (inSection && line.empty()) {
      inSection = false;
    }
  }
  return names;
}

// The option names (`--size`, and `-o` where it has no long name) of a help text's `Options:`.
std::set<std::string> optionsIn(const std::string& help) {
  std::set<std::string> names;
  std::istringstream lines(help);
  bool inSection = false;
  static const std::regex kName("(?:^|,)(--?[A-Za-z0-9][A-Za-z0-9-]*)");
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] != ' ') {  // a section's heading, or the blank line after one
      inSection = line == "Options:";
      continue;
    }
    if (!inSection || line.rfind("  -", 0) != 0) continue;  // a description's next line
    const std::string spec = line.substr(2, line.find(' ', 2) - 2);
    std::string longName, shortName;
    for (std::sregex_iterator m(spec.begin(), spec.end(), kName), end; m != end; ++m) {
      const std::string name = (*m)[1];
      (name.rfind("--", 0) == 0 ? longName : shortName) = name;
    }
    const std::string name = longName.empty() ? shortName : longName;
    if (!name.empty() && name != "--help") names.insert(name);
  }
  return names;
}

// docs/cli.md's section under the heading `## TITLE`, to the next heading of that level.
std::string sectionOf(const std::string& reference, const std::string& title) {
  const std::string heading = "## " + title;
  const std::size_t start = reference.find("\n" + heading + "\n");
  if (start == std::string::npos) return {};
  const std::size_t end = reference.find("\n## ", start + 1);
  return reference.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

bool mentions(const std::string& text, const std::string& name) {
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    const std::size_t after = at + name.size();
    const bool wholeName =
        after >= text.size() || !(std::isalnum(static_cast<unsigned char>(text[after])) ||
                                  text[after] == '-' || text[after] == '_');
    if (wholeName) return true;
  }
  return false;
}

// docs/cli.md is the reference of the command line: each command has its section, and each
// option its help prints is named there, or, for a command whose section points to the model
// options, in their section.
TEST(CommandLineDocs, EveryOptionOfEveryCommandIsInTheReference) {
  std::ifstream in(fs::path(HIRSUTE_SOURCE_DIR) / "docs" / "cli.md");
  const std::string reference{std::istreambuf_iterator<char>(in), {}};
  ASSERT_FALSE(reference.empty());
  const std::string modelOptions = sectionOf(reference, "Model options");
  ASSERT_FALSE(modelOptions.empty()) << "docs/cli.md has no section \"Model options\"";
  std::vector<std::string> commands;
  for (const std::string& name : subcommandsIn(runHirsute({"--help"}).out)) {
    const std::vector<std::string> inner = subcommandsIn(runHirsute({name, "--help"}).out);
    if (inner.empty()) commands.push_back(name);
    for (const std::string& sub : inner) commands.push_back(name + " " + sub);
  }
  ASSERT_GE(commands.size(), 9u);
  for (const std::string& command : commands) {
    std::vector<std::string> arguments;
    std::istringstream words(command);
    for (std::string word; words >> word;) arguments.push_back(word);
    arguments.push_back("--help");
    const RunResult help = runHirsute(arguments);
    ASSERT_EQ(help.exitCode, 0) << command;
    const std::string section = sectionOf(reference, "`hirsute " + command + "`");
    const bool takesModelOptions = section.find("(#model-options)") != std::string::npos;
    EXPECT_FALSE(section.empty()) << "docs/cli.md has no section `hirsute " << command << "`";
    if (section.empty()) continue;
    const std::set<std::string> options = optionsIn(help.out);
    EXPECT_FALSE(options.empty()) << command;
    for (const std::string& option : options) {
      EXPECT_TRUE(mentions(section, option) ||
                  (takesModelOptions && mentions(modelOptions, option)))
          << "docs/cli.md's `hirsute " << command << "` does not name " << option;
    }
  }
}

// --placement-seed seeds every organ's placement; --hair-seed, its name from when it placed only
// hairs, still does the same but is no longer in the help.
TEST(CommandLine, HairSeedIsAHiddenOldNameOfPlacementSeed) {
  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "hairy-cylinder";
  TemporaryFolder folder;
  const auto hairsWith = [&](const std::string& option, const std::string& seed) {
    const fs::path csv = folder.path() / (option.substr(2) + seed + ".csv");
    const RunResult run =
        runHirsute({"export", (model / "hairy-cylinder.l").string(),
                    (model / "hairy-cylinder.v").string(), option, seed, "--hairs", csv.string()});
    EXPECT_EQ(run.exitCode, 0) << run.err;
    std::ifstream in(csv, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string placed = hairsWith("--placement-seed", "7");
  EXPECT_GT(placed.size(), 1000u);
  EXPECT_EQ(hairsWith("--hair-seed", "7"), placed);
  EXPECT_NE(hairsWith("--placement-seed", "8"), placed);
  const RunResult help = runHirsute({"export", "--help"});
  EXPECT_TRUE(mentions(help.out, "--placement-seed")) << help.out;
  EXPECT_FALSE(mentions(help.out, "--hair-seed")) << help.out;
}

}  // namespace
}  // namespace hirsute
