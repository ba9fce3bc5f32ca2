// The viewer's scripted mode: the command text parsed, and its mistakes pointed at.
#include "hirsute/viewer/interaction/view_script.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "hirsute/viewer/interaction/live_organ.h"

namespace hirsute {
namespace {

using Kind = ViewCommand::Kind;

TEST(ViewScriptTest, CommandsSeparatedBySemicolonsAndLines) {
  auto script = parseViewScript(
      "rotate 30 0; step 5; screenshot a.png\n# a comment\nhairs off;zoom 1.5\nquit", "--commands");
  ASSERT_EQ(script.size(), 6u);
  EXPECT_EQ(script[0].kind, Kind::Rotate);
  EXPECT_EQ(script[0].numbers, (std::vector<double>{30, 0}));
  EXPECT_EQ(script[1].kind, Kind::Step);
  EXPECT_EQ(script[1].numbers, (std::vector<double>{5}));
  EXPECT_EQ(script[2].words, (std::vector<std::string>{"a.png"}));
  EXPECT_EQ(script[3].kind, Kind::Organ);
  EXPECT_EQ(liveOrgans()[script[3].organ]->name(), std::string("hairs"));
  EXPECT_EQ(script[3].action, -1);
  EXPECT_EQ(script[3].words, (std::vector<std::string>{"off"}));
  EXPECT_EQ(script[4].kind, Kind::Zoom);
  EXPECT_EQ(script[4].where.line, 3);
  EXPECT_EQ(script[4].where.column, 11);
  EXPECT_EQ(script[5].kind, Kind::Quit);
}

TEST(ViewScriptTest, OptionalArguments) {
  auto script = parseViewScript("step; rotate 10; screenshot x.png ui; wait-reload", "s");
  EXPECT_TRUE(script[0].numbers.empty());
  EXPECT_EQ(script[1].numbers, (std::vector<double>{10}));
  EXPECT_EQ(script[2].words.size(), 2u);
  EXPECT_EQ(script[3].kind, Kind::WaitReload);
}

void expectError(const std::string& text, const std::string& message) {
  try {
    parseViewScript(text, "--commands");
    FAIL() << "expected an error for: " << text;
  } catch (const DiagnosticError& e) {
    EXPECT_EQ(e.diagnostic().text(), message);
  }
}

TEST(ViewScriptTest, MistakesNameLineAndColumn) {
  expectError("rotate 30 0; spin 5", "--commands:1:14: error: unknown viewer command 'spin'");
  expectError("zoom big", "--commands:1:6: error: expected a number, found 'big'");
  expectError("step 1\npan 1", "--commands:2:1: error: 'pan' takes 2 arguments");
  expectError("quit now", "--commands:1:6: error: 'quit' takes 0 arguments");
  expectError("hairs maybe", "--commands:1:7: error: expected on or off, found 'maybe'");
  expectError("rotate", "--commands:1:1: error: 'rotate' takes 1 to 2 arguments");
  expectError("dynamics soon", "--commands:1:10: error: expected on or off, found 'soon'");
  expectError("droplets", "--commands:1:1: error: 'droplets' takes 1 argument");
  expectError("step; screenshot a.tiff",
              "--commands:1:18: error: 'a.tiff': the picture's format is chosen by its "
              "extension: .png, .jpg, .jpeg");
}

// Each organ of liveOrgans() adds `NAME on|off` and a command for each action that has one, with
// the action's place; no two commands share a name.
TEST(ViewScriptTest, EveryOrganAddsItsCommands) {
  const auto organs = liveOrgans();
  std::set<std::string> names;
  for (std::size_t k = 0; k < organs.size(); ++k) {
    const std::string name = organs[k]->name();
    EXPECT_TRUE(names.insert(name).second) << name;
    const auto shown = parseViewScript(name + " off", "s");
    EXPECT_EQ(shown[0].kind, Kind::Organ);
    EXPECT_EQ(shown[0].organ, k);
    EXPECT_EQ(shown[0].action, -1);
    expectError(name + " 1", "--commands:1:" + std::to_string(name.size() + 2) +
                                 ": error: expected on or off, found '1'");
    const auto actions = organs[k]->actions();
    for (std::size_t a = 0; a < actions.size(); ++a) {
      if (actions[a].command.empty()) continue;
      const std::string command(actions[a].command);
      EXPECT_TRUE(names.insert(command).second) << command;
      std::string text = command;
      for (char p : actions[a].arguments) {
        if (p == 'n') text += " 3";
        if (p == 'w') text += " x";
        if (p == 'o') text += " on";
      }
      const auto parsed = parseViewScript(text, "s");
      EXPECT_EQ(parsed[0].kind, Kind::Organ);
      EXPECT_EQ(parsed[0].organ, k);
      EXPECT_EQ(parsed[0].action, static_cast<int>(a));
    }
  }
  EXPECT_TRUE(names.contains("fur"));
  EXPECT_TRUE(names.contains("droplets"));
  EXPECT_TRUE(names.contains("dynamics"));
}

}  // namespace
}  // namespace hirsute
