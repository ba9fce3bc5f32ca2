// `hirsute feather-scan` from the command line: a feather drawn by `hirsute render` comes back as
// a commented .fea (with the scan's vane as a texture) that draws again; what is no scan of a
// feather, and a texture outside the type's folder, end the run with exit code 2 and no file. A
// FIFO or an oversized picture is refused before it is read or decoded, a failed run leaves
// every earlier output as it was, and a name's control bytes never reach the terminal.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/run_hirsute.h"

namespace {

namespace fs = std::filesystem;
using namespace hirsute::testing;

const fs::path kTypes = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "feather-types";
const fs::path kHawkScan =
    fs::path(HIRSUTE_SOURCE_DIR) / "models" / "feather-scan" / "hawk-scan.png";

// A model in `folder` that draws feather type `fea` (a file there) flat, front up, on the
// colour map's plain background: models/feather-scan's, with its own feather.
void writeModel(const fs::path& folder, const std::string& fea) {
  const fs::path model = fs::path(HIRSUTE_SOURCE_DIR) / "models" / "feather-scan";
  fs::copy_file(model / "feather-scan.map", folder / "scan.map", fs::copy_options::overwrite_existing);
  fs::copy_file(model / "scan.l", folder / "scan.l", fs::copy_options::overwrite_existing);
  const std::string view = readText(model / "feather-scan.v");
  std::ofstream(folder / "scan.v") << view.substr(0, view.find("\nfeather:") + 1) << "feather: " << fea
                                   << "\n";
}

// The number after `keyword:` in .fea text.
double valueOf(const std::string& text, const std::string& keyword) {
  const std::size_t at = text.find("\n" + keyword + ":");
  if (at == std::string::npos) return -1;
  std::istringstream in(text.substr(at + keyword.size() + 2));
  double value = -1;
  in >> value;
  return value;
}

TEST(FeatherScanCommand, ADrawnFeatherComesBackAsATypeThatDrawsAgain) {
  TemporaryFolder scanFolder, typeFolder;
  fs::copy_file(kTypes / "budgie.fea", scanFolder.path() / "budgie.fea");
  fs::copy_file(kTypes / "budgie.png", scanFolder.path() / "budgie.png");
  writeModel(scanFolder.path(), "budgie.fea");
  const fs::path scan = scanFolder.path() / "scan.png";
  RunResult run = runHirsute({"render", (scanFolder.path() / "scan.l").string(),
                              (scanFolder.path() / "scan.v").string(), "-o", scan.string(),
                              "--size", "420x700"});
  ASSERT_EQ(run.exitCode, 0) << run.err;

  const fs::path type = typeFolder.path() / "found.fea";
  run = runHirsute({"feather-scan", scan.string(), "-o", type.string(), "--length", "2.45",
                    "--texture", (typeFolder.path() / "found-vane.png").string()});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("written to"), std::string::npos) << run.out;
  const std::string text = readText(type);
  EXPECT_EQ(text.rfind("# A feather type read from the scan scan.png", 0), 0u) << text;
  EXPECT_NEAR(valueOf(text, "rachis length"), 2.2, 0.15);
  EXPECT_NEAR(valueOf(text, "calamus length"), 0.25, 0.08);
  EXPECT_NE(text.find("rachis front curvature: 0"), std::string::npos);
  EXPECT_NE(text.find("key barb: left"), std::string::npos);
  EXPECT_NE(text.find("texture: found-vane.png vane"), std::string::npos);
  EXPECT_EQ(readText(typeFolder.path() / "found-vane.png").substr(1, 3), "PNG");

  // The type draws: its texture resolves beside it.
  writeModel(typeFolder.path(), "found.fea");
  run = runHirsute({"render", (typeFolder.path() / "scan.l").string(),
                    (typeFolder.path() / "scan.v").string(), "-o",
                    (typeFolder.path() / "again.png").string(), "--size", "120x200"});
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(run.err.find("warning") == std::string::npos) << run.err;
}

TEST(FeatherScanCommand, WhatIsNoScanOfAFeatherIsBadInput) {
  TemporaryFolder folder;
  const fs::path type = folder.path() / "type.fea";
  std::ofstream(folder.path() / "text.png") << "not an image\n";
  RunResult run = runHirsute({"feather-scan", (folder.path() / "text.png").string(), "-o", type.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("text.png"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("cannot decode"), std::string::npos) << run.err;

  {  // a plain white page
    std::ofstream blank(folder.path() / "blank.ppm", std::ios::binary);
    blank << "P6\n64 64\n255\n" << std::string(64 * 64 * 3, '\xff');
  }
  run = runHirsute({"feather-scan", (folder.path() / "blank.ppm").string(), "-o", type.string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("blank.ppm: error: no feather found"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(type));

  // A texture the .fea could not name from its own folder.
  run = runHirsute({"feather-scan", (folder.path() / "blank.ppm").string(), "-o",
                    (folder.path() / "types" / "type.fea").string(), "--texture",
                    (folder.path() / "vane.png").string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("must lie in the folder of the .fea"), std::string::npos) << run.err;
  run = runHirsute({"feather-scan", (folder.path() / "blank.ppm").string(), "-o", type.string(),
                    "--dpi", "nan"});
  EXPECT_EQ(run.exitCode, 2) << run.err;
}

// A PNG's signature and header chunk alone: an 8-bit RGB picture of width × height whose pixels
// never come (stb_image checks no CRC).
std::string pngHeaderOnly(std::uint32_t width, std::uint32_t height) {
  const auto bigEndian = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  return std::string("\x89PNG\r\n\x1a\n", 8) + bigEndian(13) + "IHDR" + bigEndian(width) +
         bigEndian(height) + std::string("\x08\x02\x00\x00\x00", 5) + bigEndian(0) + bigEndian(0) +
         "IEND" + bigEndian(0);
}

TEST(FeatherScanCommand, AFifoIsRefusedAtOnce) {
  TemporaryFolder folder;
  const fs::path fifo = folder.path() / "scan.png";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const RunResult run =
      runHirsute({"feather-scan", fifo.string(), "-o", (folder.path() / "type.fea").string()});
  ASSERT_FALSE(run.killed) << "feather-scan waited on the FIFO";
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find(fifo.string() + ": error: cannot read the scan: it is a FIFO, not a "
                                         "regular file"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(folder.path() / "type.fea"));
}

// The size is read from the picture's header: a scan over the limit is refused before its
// pixels are decoded (this one has none to decode).
TEST(FeatherScanCommand, AScanOverTheLimitIsRefusedByItsHeader) {
  TemporaryFolder folder;
  const fs::path scan = folder.path() / "large.png";
  std::ofstream(scan, std::ios::binary) << pngHeaderOnly(8192, 8192);
  const RunResult run =
      runHirsute({"feather-scan", scan.string(), "-o", (folder.path() / "type.fea").string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find(scan.string() + ": error: the scan has 8192 × 8192 pixels, more than 16 "
                                         "Mpixel (the limit)"),
            std::string::npos)
      << run.err;
}

TEST(FeatherScanCommand, AFailedRunLeavesTheTextureAsItWas) {
  TemporaryFolder folder;
  const fs::path texture = folder.path() / "keep.png";
  std::ofstream(texture) << "the texture of an earlier run\n";
  // The type cannot be written (a folder has its name): the run fails after the scan was read.
  const fs::path type = folder.path() / "type.fea";
  fs::create_directory(type);
  const RunResult run =
      runHirsute({"feather-scan", kHawkScan.string(), "-o", type.string(), "--length", "12.5",
                  "--texture", texture.string(), "--texture-size", "16"});
  EXPECT_EQ(run.exitCode, 1) << run.err;
  EXPECT_NE(run.err.find("hirsute: error: " + type.string() + ": cannot write"), std::string::npos)
      << run.err;
  EXPECT_EQ(readText(texture), "the texture of an earlier run\n");
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"keep.png", "type.fea"}));
}

// CLI11's own messages quote the arguments: their escape bytes are shown, not sent.
TEST(FeatherScanCommand, AMissingScansNameIsShownEscaped) {
  TemporaryFolder folder;
  const std::string name = (folder.path() /
                            "\x1b]0;title\x07\x9b"
                            "31mscan.png")
                               .string();
  const RunResult run =
      runHirsute({"feather-scan", name, "-o", (folder.path() / "type.fea").string()});
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("hirsute: error: "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("\\x1b]0;title\\x07\\x9b31mscan.png"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find('\x1b'), std::string::npos);
  EXPECT_EQ(run.err.find('\x07'), std::string::npos);
  EXPECT_EQ(run.err.find('\x9b'), std::string::npos);
}

}  // namespace
